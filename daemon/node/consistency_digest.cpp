// The consistency digest (what goes in and why: consistency_digest.h).
#include "node/consistency_digest.h"

#include <cryptopp/sha.h>
#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor.pb.h>
#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

#include "core/node_links.h"
#include "mac/mac_factory.h"
#include "util/hex.h"

namespace acomms::node {
namespace {

namespace gp = google::protobuf;

std::string deterministic_bytes(const gp::Message& message) {
  std::string out;
  {
    gp::io::StringOutputStream stream(&out);
    gp::io::CodedOutputStream coded(&stream);
    coded.SetSerializationDeterministic(true);
    message.SerializeToCodedStream(&coded);
  }
  return out;
}

// Every message and enum type `root`'s fields use, transitively, by full
// name (the map's order makes the text canonical).
void collect(const gp::Descriptor* message, std::map<std::string, const gp::Descriptor*>* messages,
             std::map<std::string, const gp::EnumDescriptor*>* enums) {
  if (!messages->emplace(message->full_name(), message).second) return;
  for (int i = 0; i < message->field_count(); ++i) {
    const gp::FieldDescriptor* field = message->field(i);
    if (field->message_type() != nullptr) collect(field->message_type(), messages, enums);
    if (field->enum_type() != nullptr) enums->emplace(field->enum_type()->full_name(), field->enum_type());
  }
}

// One message type without its nested declarations (those it uses are
// listed on their own; those it does not use change nothing on the wire),
// fields by number: declaration order is not part of the wire format.
std::string message_bytes(const gp::Descriptor* message) {
  gp::DescriptorProto proto;
  message->CopyTo(&proto);
  proto.clear_nested_type();
  proto.clear_enum_type();
  auto* fields = proto.mutable_field();
  std::sort(fields->pointer_begin(), fields->pointer_end(),
            [](const gp::FieldDescriptorProto* a, const gp::FieldDescriptorProto* b) { return a->number() < b->number(); });
  return deterministic_bytes(proto);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace

std::string canonical_definitions(const dccl::Codec& codec) {
  std::vector<const dccl::TypeInfo*> types = codec.types();
  std::sort(types.begin(), types.end(), [](const dccl::TypeInfo* a, const dccl::TypeInfo* b) {
    return std::pair(a->omit_id ? -1 : a->id, a->name) < std::pair(b->omit_id ? -1 : b->id, b->name);
  });
  std::string out;
  for (const dccl::TypeInfo* type : types) {
    out += "type " + (type->omit_id ? std::string("omit_id") : std::to_string(type->id)) + " " + type->name + "\n";
    std::map<std::string, const gp::Descriptor*> messages;
    std::map<std::string, const gp::EnumDescriptor*> enums;
    if (type->descriptor != nullptr) collect(type->descriptor, &messages, &enums);
    for (const auto& [name, message] : messages) {
      const std::string bytes = message_bytes(message);
      out += "message " + name + " " + std::to_string(bytes.size()) + "\n" + bytes + "\n";
    }
    for (const auto& [name, enumeration] : enums) {
      gp::EnumDescriptorProto proto;
      enumeration->CopyTo(&proto);
      const std::string bytes = deterministic_bytes(proto);
      out += "enum " + name + " " + std::to_string(bytes.size()) + "\n" + bytes + "\n";
    }
  }
  return out;
}

std::string canonical_mac(const v1::MacConfig& config, const mac::Cycle& cycle) {
  const std::string& name = config.name();
  const std::string epoch = config.has_epoch() ? number(config.epoch()) : "midnight";
  if (name == "fixed") {
    std::string out = "fixed epoch " + epoch + "\n";
    for (const mac::Slot& slot : cycle) {
      out += "slot src " + std::to_string(slot.src) + " dest " + std::to_string(slot.dest) + " rate " +
             std::to_string(slot.rate) + " seconds " + number(slot.seconds) + "\n";
    }
    return out;
  }
  if (name == "auto_discovery") {
    return "auto_discovery epoch " + epoch + " slot_seconds " + number(config.slot_seconds()) + " rate " +
           std::to_string(config.rate()) + " coolness " + std::to_string(config.coolness()) + " expire_cycles " +
           std::to_string(config.expire_cycles()) + " blank_rule " +
           (config.blank_rule().empty() ? std::string("anywhere") : config.blank_rule()) + "\n";
  }
  // "polled", "none" (or unset): the cycle is the polling master's alone.
  return "master-driven\n";
}

uint32_t consistency_digest(std::string_view canonical_definitions, std::string_view canonical_mac) {
  // Lengths first, so no split of the two texts collides with another.
  const std::string head = "acomms consistency v1\ndefinitions " + std::to_string(canonical_definitions.size()) +
                           "\nmac " + std::to_string(canonical_mac.size()) + "\n";
  CryptoPP::SHA256 sha;
  sha.Update(reinterpret_cast<const CryptoPP::byte*>(head.data()), head.size());
  sha.Update(reinterpret_cast<const CryptoPP::byte*>(canonical_definitions.data()), canonical_definitions.size());
  sha.Update(reinterpret_cast<const CryptoPP::byte*>(canonical_mac.data()), canonical_mac.size());
  CryptoPP::byte hash[CryptoPP::SHA256::DIGESTSIZE];
  sha.Final(hash);
  return (uint32_t{hash[0]} << 24) | (uint32_t{hash[1]} << 16) | (uint32_t{hash[2]} << 8) | uint32_t{hash[3]};
}

std::string digest_hex(uint32_t digest) {
  char text[9];
  std::snprintf(text, sizeof text, "%08x", digest);
  return text;
}

std::optional<uint32_t> parse_digest(std::string_view hex) {
  if (hex.size() != 8) return std::nullopt;
  uint32_t digest = 0;
  for (char c : hex) {
    const int value = util::hex_digit_value(c);
    if (value < 0) return std::nullopt;
    digest = (digest << 4) | static_cast<uint32_t>(value);
  }
  return digest;
}

std::vector<std::pair<std::string, uint32_t>> config_digests(const v1::Config& config, const dccl::Codec& codec) {
  const std::string definitions = canonical_definitions(codec);
  std::vector<std::pair<std::string, uint32_t>> out;
  for (const v1::LinkConfig& link : core::node_links(config)) {
    out.emplace_back(link.name(),
                     consistency_digest(definitions, canonical_mac(link.mac(), mac::cycle_from_config(link.mac()))));
  }
  return out;
}

}  // namespace acomms::node
