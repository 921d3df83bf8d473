#include "dccl/options.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor.pb.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/message.h>

#include <type_traits>

namespace acomms::dccl {
namespace gp = google::protobuf;

namespace {

// Typed getters by option name; `has` is set when the option was given.
template <typename T>
T get(const gp::Message& m, const char* name, bool* has = nullptr) {
  const gp::FieldDescriptor* f = m.GetDescriptor()->FindFieldByName(name);
  if (f == nullptr) {
    if (has) *has = false;
    return T{};
  }
  const gp::Reflection* r = m.GetReflection();
  if (has) *has = r->HasField(m, f);
  if constexpr (std::is_same_v<T, std::string>) {
    return r->GetString(m, f);
  } else if constexpr (std::is_same_v<T, bool>) {
    return r->GetBool(m, f);
  } else if constexpr (std::is_same_v<T, int32_t>) {
    return r->GetInt32(m, f);
  } else if constexpr (std::is_same_v<T, uint32_t>) {
    return r->GetUInt32(m, f);
  } else {
    return r->GetDouble(m, f);
  }
}

}  // namespace

OptionReader::OptionReader(const gp::DescriptorPool* pool)
    : pool_(pool), factory_(std::make_unique<gp::DynamicMessageFactory>(pool)) {
  field_ext_ = pool_->FindExtensionByName("dccl.field");
  msg_ext_ = pool_->FindExtensionByName("dccl.msg");
}

OptionReader::~OptionReader() = default;

// Descriptors keep their options in the compiled google.protobuf.*Options
// classes, where extensions unknown to the compiled-in pool (dccl.* here)
// sit as unknown fields. Re-parsing the serialized options against our pool
// turns them into a proper dynamic message, extensions of extensions
// (plugin options on DCCLFieldOptions) included.
const gp::Message& OptionReader::extension_of(const gp::Message& options,
                                              const char* options_type,
                                              const gp::FieldDescriptor* ext) {
  const gp::Descriptor* type = pool_->FindMessageTypeByName(options_type);
  std::unique_ptr<gp::Message> parsed(factory_->GetPrototype(type)->New());
  std::string bytes = options.SerializeAsString();
  gp::io::CodedInputStream in(reinterpret_cast<const uint8_t*>(bytes.data()),
                              static_cast<int>(bytes.size()));
  in.SetExtensionRegistry(pool_, factory_.get());
  parsed->MergePartialFromCodedStream(&in);
  const gp::Message& value = parsed->GetReflection()->GetMessage(*parsed, ext, factory_.get());
  owned_.push_back(std::move(parsed));
  return value;
}

MessageOptions OptionReader::message_options(const gp::Descriptor* type) {
  MessageOptions o;
  if (!available()) return o;
  const gp::Message& m = extension_of(type->options(), "google.protobuf.MessageOptions", msg_ext_);
  const gp::Message& container = *owned_.back();
  o.present = container.GetReflection()->HasField(container, msg_ext_);
  o.id = get<int32_t>(m, "id", &o.has_id);
  o.max_bytes = get<uint32_t>(m, "max_bytes", &o.has_max_bytes);
  o.codec = get<std::string>(m, "codec");
  o.codec_group = get<std::string>(m, "codec_group");
  o.codec_version = get<int32_t>(m, "codec_version", &o.has_codec_version);
  o.omit_id = get<bool>(m, "omit_id");
  return o;
}

FieldOptions OptionReader::field_options(const gp::FieldDescriptor* field, const gp::Message** raw) {
  FieldOptions o;
  if (!available()) return o;
  const gp::Message& m = extension_of(field->options(), "google.protobuf.FieldOptions", field_ext_);
  if (raw) *raw = &m;
  o.codec = get<std::string>(m, "codec", &o.has_codec);
  o.omit = get<bool>(m, "omit");
  o.in_head = get<bool>(m, "in_head");
  o.precision = get<int32_t>(m, "precision", &o.has_precision);
  o.min = get<double>(m, "min", &o.has_min);
  o.max = get<double>(m, "max", &o.has_max);
  o.num_days = get<uint32_t>(m, "num_days");
  o.static_value = get<std::string>(m, "static_value");
  o.max_length = get<uint32_t>(m, "max_length", &o.has_max_length);
  o.max_repeat = get<uint32_t>(m, "max_repeat", &o.has_max_repeat);
  o.packed_enum = get<bool>(m, "packed_enum");
  o.resolution = get<double>(m, "resolution", &o.has_resolution);
  o.min_repeat = get<uint32_t>(m, "min_repeat");
  if (const gp::FieldDescriptor* dc = m.GetDescriptor()->FindFieldByName("dynamic_conditions")) {
    o.has_dynamic_conditions = m.GetReflection()->HasField(m, dc);
  }
  return o;
}

}  // namespace acomms::dccl
