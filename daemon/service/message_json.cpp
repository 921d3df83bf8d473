#include "service/message_json.h"

#include <google/protobuf/util/json_util.h>

namespace acomms::service {

std::string to_json(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  std::string json;
  if (!google::protobuf::util::MessageToJsonString(message, &json, options).ok()) {
    // Only possible for messages JSON cannot express (e.g. unresolvable Any);
    // DCCL types have none, so say so rather than fail the whole call.
    return "{}";
  }
  return json;
}

}  // namespace acomms::service
