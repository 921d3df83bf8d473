#include "dccl/message_json.h"

#include <google/protobuf/descriptor.pb.h>
#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/type_resolver.h>
#include <google/protobuf/util/type_resolver_util.h>

#include <memory>

namespace acomms::dccl {
namespace {

namespace pb = google::protobuf;

std::string json_of(const pb::Message& message, bool indented) {
  // Through the binary form: MessageToJsonString insists on required fields.
  static constexpr const char* kUrlPrefix = "type.googleapis.com";
  const pb::Descriptor* type = message.GetDescriptor();
  std::unique_ptr<pb::util::TypeResolver> resolver(
      pb::util::NewTypeResolverForDescriptorPool(kUrlPrefix, type->file()->pool()));
  pb::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  options.add_whitespace = indented;
  std::string json;
  if (!pb::util::BinaryToJsonString(resolver.get(), std::string(kUrlPrefix) + "/" + type->full_name(),
                                    message.SerializePartialAsString(), &json, options)
           .ok()) {
    // Only possible for messages JSON cannot express (e.g. unresolvable Any);
    // DCCL types have none.
    return "{}";
  }
  return json;
}

void make_optional(pb::DescriptorProto* type) {
  for (auto& field : *type->mutable_field()) {
    if (field.label() == pb::FieldDescriptorProto::LABEL_REQUIRED) {
      field.set_label(pb::FieldDescriptorProto::LABEL_OPTIONAL);
    }
  }
  for (auto& nested : *type->mutable_nested_type()) make_optional(&nested);
}

}  // namespace

std::string message_json(const pb::Message& message) { return json_of(message, /*indented=*/false); }

std::string indented_message_json(const pb::Message& message) { return json_of(message, /*indented=*/true); }

void JsonReader::add_file(const pb::FileDescriptor* file) {
  if (pool_.FindFileByName(file->name()) != nullptr) return;
  for (int i = 0; i < file->dependency_count(); ++i) add_file(file->dependency(i));
  pb::FileDescriptorProto proto;
  file->CopyTo(&proto);
  for (auto& type : *proto.mutable_message_type()) make_optional(&type);
  pool_.BuildFile(proto);  // cannot fail: the original built
}

const pb::Descriptor* JsonReader::relaxed(const pb::Descriptor* type) {
  std::lock_guard lock(mutex_);
  add_file(type->file());
  return pool_.FindMessageTypeByName(type->full_name());
}

std::string JsonReader::parse(const std::string& json, pb::Message* message) {
  const pb::Descriptor* type = relaxed(message->GetDescriptor());
  if (type == nullptr) return "cannot parse JSON for " + message->GetDescriptor()->full_name();
  std::unique_ptr<pb::Message> loose(factory_.GetPrototype(type)->New());
  pb::util::Status parsed = pb::util::JsonStringToMessage(json, loose.get());
  if (!parsed.ok()) {
    std::string why(parsed.message());
    if (why.rfind(": ", 0) == 0) why.erase(0, 2);  // the parser leaves an empty path in front
    return why.empty() ? "not valid JSON" : why;
  }
  if (!message->ParsePartialFromString(loose->SerializePartialAsString())) return "does not match the type";
  return {};
}

}  // namespace acomms::dccl
