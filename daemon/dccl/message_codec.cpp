#include "dccl/message_codec.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <algorithm>

#include "dccl/numeric.h"
#include "dccl/registry.h"
#include "util/saturating.h"

namespace acomms::dccl {
namespace gp = google::protobuf;

namespace {

using util::saturating_add;

[[noreturn]] void throw_truncated(const std::string& path, const TruncatedRead& t) {
  throw decode_error(path + ": message truncated at bit " + std::to_string(t.position) + " (needs " +
                     std::to_string(t.needed) + " bits, " + std::to_string(t.left) + " left)");
}

}  // namespace

// ------------------------------------------------------------------ MessageBody

// Body layout: for each oneof, ceil_log2(members + 1) bits (0 = unset, else
// member index + 1); then the fields in declaration order, skipping oneof
// members that are not the one set.
void MessageBody::encode(const gp::Message& msg, BitWriter& out, const EncodeContext& ctx) const {
  if (oneofs_.empty()) {
    for (const Slot& slot : slots_) slot.codec->encode(msg, out, ctx);
    return;
  }
  const gp::Reflection* r = msg.GetReflection();
  std::vector<const gp::FieldDescriptor*> chosen(oneofs_.size());
  for (size_t i = 0; i < oneofs_.size(); ++i) {
    chosen[i] = r->GetOneofFieldDescriptor(msg, oneofs_[i].oneof);
    out.write(chosen[i] ? chosen[i]->index_in_oneof() + 1 : 0, oneofs_[i].bits);
  }
  for (const Slot& slot : slots_) {
    if (slot.oneof >= 0 && chosen[slot.oneof] != slot.field) continue;
    slot.codec->encode(msg, out, ctx);
  }
}

void MessageBody::decode(BitReader& in, gp::Message* msg, const DecodeContext& ctx) const {
  std::vector<const gp::FieldDescriptor*> chosen(oneofs_.size());
  for (size_t i = 0; i < oneofs_.size(); ++i) {
    uint64_t v;
    try {
      v = in.read(oneofs_[i].bits);
    } catch (const TruncatedRead& t) {
      throw_truncated(oneofs_[i].path, t);
    }
    const gp::OneofDescriptor* o = oneofs_[i].oneof;
    // A selector past the last member decodes as "none set".
    chosen[i] = (v >= 1 && v <= static_cast<uint64_t>(o->field_count())) ? o->field(static_cast<int>(v - 1)) : nullptr;
  }
  for (const Slot& slot : slots_) {
    if (slot.oneof >= 0 && chosen[slot.oneof] != slot.field) continue;
    try {
      slot.codec->decode(in, msg, ctx);
    } catch (const TruncatedRead& t) {
      throw_truncated(slot.path, t);
    }
  }
}

SizeBits MessageBody::size() const {
  SizeBits total;
  std::vector<uint64_t> oneof_max(oneofs_.size(), 0);
  for (size_t i = 0; i < oneofs_.size(); ++i) {
    total.min = saturating_add(total.min, oneofs_[i].bits);
    total.max = saturating_add(total.max, oneofs_[i].bits);
  }
  for (const Slot& slot : slots_) {
    SizeBits s = slot.codec->size();
    if (slot.oneof >= 0) {
      oneof_max[slot.oneof] = std::max(oneof_max[slot.oneof], s.max);
      continue;
    }
    total.min = saturating_add(total.min, s.min);
    total.max = saturating_add(total.max, s.max);
  }
  for (uint64_t m : oneof_max) total.max = saturating_add(total.max, m);
  return total;
}

// ------------------------------------------------------------------ MessageCompiler

MessageCompiler::MessageCompiler(const CodecRegistry* registry, OptionReader* options,
                                 const gp::DescriptorPool* pool, CompileSettings settings)
    : registry_(registry), options_(options), pool_(pool), settings_(std::move(settings)) {}

void MessageCompiler::compile_top(const gp::Descriptor* type, MessageBody* head, MessageBody* body) {
  stack_.push_back(type);
  compile_fields(type, type->full_name(), head, body);
  stack_.pop_back();
}

std::shared_ptr<MessageBody> MessageCompiler::compile_embedded(const gp::Descriptor* type,
                                                               const std::string& path) {
  if (std::find(stack_.begin(), stack_.end(), type) != stack_.end()) {
    throw schema_error(path + ": recursive message type " + type->full_name() + " is not supported");
  }
  auto body = std::make_shared<MessageBody>();
  stack_.push_back(type);
  compile_fields(type, path, nullptr, body.get());
  stack_.pop_back();
  return body;
}

void MessageCompiler::compile_fields(const gp::Descriptor* type, const std::string& prefix,
                                     MessageBody* head, MessageBody* body) {
  const int depth = static_cast<int>(stack_.size()) - 1;
  // Oneof selectors come first in the body.
  std::vector<int> oneof_slot(type->oneof_decl_count(), -1);
  int oneof_count = 0;
  for (int i = 0; i < type->oneof_decl_count(); ++i) {
    const gp::OneofDescriptor* o = type->oneof_decl(i);
    std::string path = prefix + "." + o->name();
    if (settings_.codec_version < 4) {
      errors_.push_back(path + ": oneof needs codec_version 4 (message has " +
                        std::to_string(settings_.codec_version) + ")");
      continue;
    }
    body->add_oneof({o, ceil_log2(static_cast<uint64_t>(o->field_count()) + 1), path});
    oneof_slot[i] = oneof_count++;
  }

  for (int i = 0; i < type->field_count(); ++i) {
    const gp::FieldDescriptor* field = type->field(i);
    const gp::Message* raw = nullptr;
    FieldOptions fo = options_->field_options(field, &raw);
    if (fo.omit) continue;
    std::string path = prefix + "." + field->name();
    const gp::OneofDescriptor* oneof = field->containing_oneof();
    if (oneof != nullptr && oneof_slot[oneof->index()] < 0) continue;  // already reported
    bool in_head = fo.in_head && head != nullptr;

    size_t info_index = fields_.size();
    fields_.push_back(FieldInfo{path, "", field, {}, in_head, depth, 0});
    std::string codec_name;
    std::unique_ptr<FieldCodec> codec;
    try {
      if (in_head && oneof != nullptr) throw schema_error(path + ": a oneof member cannot be in_head");
      codec = compile_field(field, path, fo, raw, &codec_name);
      SizeBits size = codec->size();
      if (in_head && size.min != size.max) {
        throw schema_error(path + ": in_head field must have a fixed size (has " + std::to_string(size.min) +
                           " to " + std::to_string(size.max) + " bits)");
      }
      fields_[info_index].codec = codec_name;
      fields_[info_index].bits = size;
      fields_[info_index].resolution = codec->resolution();
    } catch (const TypeRefused& e) {
      refusals_.push_back(e.what());
      continue;
    } catch (const Error& e) {
      errors_.push_back(e.what());
      continue;
    }
    MessageBody::Slot slot{std::move(codec), field, oneof ? oneof_slot[oneof->index()] : -1, path};
    (in_head ? head : body)->add_slot(std::move(slot));
  }
}

std::unique_ptr<FieldCodec> MessageCompiler::compile_field(const gp::FieldDescriptor* field,
                                                           const std::string& path,
                                                           const FieldOptions& fo, const gp::Message* raw,
                                                           std::string* codec_name) {
  auto fail = [&](const std::string& rule) { throw schema_error(path + ": " + rule); };
  if (fo.has_dynamic_conditions) {
    // The reference evaluates them per message (bounds and presence that
    // depend on other fields); encoding without them would put other bytes
    // on the wire than a fielded vehicle expects.
    throw TypeRefused(path + ": (dccl.field).dynamic_conditions is not supported by acommsd");
  }
  if (fo.has_precision && fo.has_resolution) fail("precision and resolution are both set");
  if (field->is_repeated()) {
    if (!fo.has_max_repeat) fail("repeated field needs (dccl.field).max_repeat");
    if (fo.max_repeat < fo.min_repeat) {
      fail("max_repeat " + std::to_string(fo.max_repeat) + " is less than min_repeat " +
           std::to_string(fo.min_repeat));
    }
  }

  std::string name = fo.has_codec ? fo.codec : (settings_.codec_group.empty() ? "_default" : settings_.codec_group);
  const FieldCodecFactory* factory = registry_->find(name, settings_.codec_version, codec_name);
  if (factory == nullptr) fail("unknown field codec \"" + name + "\"");

  const int v = settings_.codec_version;
  FieldContext ctx;
  ctx.field = field;
  ctx.path = path;
  ctx.codec_name = *codec_name;
  ctx.options = fo;
  ctx.raw_options = raw;
  ctx.pool = pool_;
  ctx.codec_version = v;
  ctx.required = field->is_required() || (field->is_repeated() && v >= 3) ||
                 (field->real_containing_oneof() != nullptr && v >= 4);
  ctx.compiler = this;
  std::unique_ptr<FieldCodec> codec = (*factory)(ctx);
  if (codec == nullptr) fail("codec \"" + *codec_name + "\" did not build");
  return codec;
}

}  // namespace acomms::dccl
