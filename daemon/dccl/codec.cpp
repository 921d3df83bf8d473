// Codec joins schema loading and the wire: it finds a loaded type's plan
// (by descriptor, name or the id that starts the bytes) and hands it to the
// wire format. What each half does is in schema_loader.h and wire_format.h.
#include "dccl/codec.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include "dccl/schema_loader.h"
#include "dccl/wire_format.h"

namespace acomms::dccl {
namespace gp = google::protobuf;

Codec::Codec() : schema_(std::make_unique<SchemaLoader>()), wire_(std::make_unique<WireFormat>()) {}

Codec::~Codec() = default;

CodecRegistry& Codec::registry() { return schema_->registry(); }

void Codec::add_include_dir(const std::string& dir) { schema_->add_include_dir(dir); }

const std::vector<std::string>& Codec::include_dirs() const { return schema_->include_dirs(); }

std::vector<const TypeInfo*> Codec::load(const std::string& proto_file, const std::vector<std::string>& include_dirs) {
  return schema_->load(proto_file, include_dirs);
}

const std::map<std::string, std::string>& Codec::refused_types() const { return schema_->refused_types(); }

std::string Codec::refusal(std::string_view full_name) const {
  const auto& refused = schema_->refused_types();
  auto it = refused.find(std::string(full_name));
  return it == refused.end() ? std::string() : it->second;
}

const TypeInfo* Codec::find_type(std::string_view full_name) const {
  const TypePlan* plan = schema_->find(full_name);
  return plan ? &plan->info : nullptr;
}

void Codec::reserve_id(int id, const std::string& owner) { schema_->reserve_id(id, owner); }

const TypeInfo* Codec::find_id(int id) const {
  const TypePlan* plan = schema_->find_id(id);
  return plan ? &plan->info : nullptr;
}

std::vector<const TypeInfo*> Codec::types() const { return schema_->types(); }

std::unique_ptr<gp::Message> Codec::new_message(std::string_view full_name) const {
  const TypePlan* plan = schema_->find(full_name);
  if (plan == nullptr) {
    if (std::string why = refusal(full_name); !why.empty()) {
      throw encode_error("unknown type " + std::string(full_name) + " (refused at load: " + why + ")");
    }
    throw encode_error("DCCL type " + std::string(full_name) + " is not loaded");
  }
  return std::unique_ptr<gp::Message>(plan->prototype->New());
}

std::string Codec::encode(const gp::Message& msg) const {
  if (const TypePlan* plan = schema_->find(msg.GetDescriptor())) return wire_->encode(*plan, msg);
  // Same type from another pool (e.g. generated code): copy through the wire.
  const TypePlan* plan = schema_->find(msg.GetDescriptor()->full_name());
  if (plan == nullptr) throw encode_error("DCCL type " + msg.GetDescriptor()->full_name() + " is not loaded");
  std::unique_ptr<gp::Message> copy(plan->prototype->New());
  copy->ParsePartialFromString(msg.SerializePartialAsString());
  return wire_->encode(*plan, *copy);
}

std::vector<std::unique_ptr<gp::Message>> Codec::decode(std::string_view bytes) const {
  std::vector<std::unique_ptr<gp::Message>> out;
  size_t pos = 0;
  while (pos < bytes.size()) {
    std::string_view rest = bytes.substr(pos);
    int id = id_of(rest);
    const TypePlan* plan = schema_->find_id(id);
    if (plan == nullptr) throw decode_error("unknown DCCL id " + std::to_string(id));
    size_t used = 0;
    out.push_back(wire_->decode(*plan, rest, &used));
    if (used == 0) break;  // cannot happen with an id; guards against looping
    pos += used;
  }
  return out;
}

std::unique_ptr<gp::Message> Codec::decode_as(std::string_view full_name, std::string_view bytes,
                                              size_t* consumed) const {
  const TypePlan* plan = schema_->find(full_name);
  if (plan == nullptr) throw decode_error("DCCL type " + std::string(full_name) + " is not loaded");
  if (!plan->info.omit_id) {
    int id = id_of(bytes);
    if (id != plan->info.id) {
      throw decode_error("DCCL id " + std::to_string(id) + " is not " + plan->info.name + " (id " +
                         std::to_string(plan->info.id) + ")");
    }
  }
  return wire_->decode(*plan, bytes, consumed);
}

int Codec::id_of(std::string_view bytes) const { return WireFormat::id_of(bytes); }

void Codec::set_crypto(std::string_view passphrase, std::set<int> exempt_ids) {
  wire_->set_crypto(passphrase, std::move(exempt_ids));
}

void Codec::clear_crypto() { wire_->clear_crypto(); }

void Codec::set_authentication(std::shared_ptr<const MessageAuthenticator> authenticator,
                               std::set<std::string> types) {
  for (const std::string& type : types) {
    const TypePlan* plan = schema_->find(type);
    if (plan == nullptr) throw Error(Error::Kind::kSchema, "authenticated type " + type + " is not loaded");
    // Without an id a receiver cannot tell which messages carry a trailer.
    if (plan->info.omit_id) throw Error(Error::Kind::kSchema, "authenticated type " + type + " has omit_id");
    // max_bytes is the frame the type was sized for: a sealed message
    // larger than that could wait for a frame that never comes.
    if (authenticator) {
      const uint64_t sealed = plan->info.max_size_bytes() + authenticator->trailer_bytes();
      if (sealed > plan->info.max_bytes) {
        throw Error(Error::Kind::kSchema,
                    "authenticated type " + type + " is up to " + std::to_string(sealed) + " bytes sealed (" +
                        std::to_string(plan->info.max_size_bytes()) + " DCCL + " +
                        std::to_string(authenticator->trailer_bytes()) + " trailer at " +
                        std::to_string(authenticator->tag_bits()) + "-bit tags), more than its max_bytes " +
                        std::to_string(plan->info.max_bytes) + ": raise max_bytes or shorten auth.tag_bits");
      }
    }
  }
  wire_->set_authentication(std::move(authenticator), std::move(types));
}

const MessageAuthenticator* Codec::authenticator() const { return wire_->authenticator(); }

bool Codec::authenticated(std::string_view full_name) const {
  const TypePlan* plan = schema_->find(full_name);
  return plan != nullptr && wire_->authenticates(plan->info);
}

void Codec::set_strict(bool strict) { wire_->set_strict(strict); }
bool Codec::strict() const { return wire_->strict(); }

void Codec::set_clock(std::function<double()> clock) { wire_->set_clock(std::move(clock)); }

}  // namespace acomms::dccl
