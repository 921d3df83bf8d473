#pragma once
// Messages as JSON for clients: proto field names (as in the .proto, which
// is what operators read), defaults left out.

#include <google/protobuf/message.h>

#include <string>

namespace acomms::service {

std::string to_json(const google::protobuf::Message& message);

}  // namespace acomms::service
