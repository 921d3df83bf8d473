#include "dccl/message_json.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/type_resolver.h>
#include <google/protobuf/util/type_resolver_util.h>

#include <memory>

namespace acomms::dccl {

namespace pb = google::protobuf;

std::string to_json(const pb::Message& message, bool pretty) {
  // Through the binary form: MessageToJsonString insists on required fields.
  static constexpr const char* kUrlPrefix = "type.googleapis.com";
  const pb::Descriptor* type = message.GetDescriptor();
  std::unique_ptr<pb::util::TypeResolver> resolver(
      pb::util::NewTypeResolverForDescriptorPool(kUrlPrefix, type->file()->pool()));
  pb::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  options.add_whitespace = pretty;
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

}  // namespace acomms::dccl
