#pragma once
// DCCL messages as JSON for people and clients: proto field names (as in
// the .proto), defaults left out. Works on partial messages too: a decoded
// message may lack a required field legitimately ((dccl.field).omit), and
// a message being typed in has its required fields filled last.
//
// Thread-safe: a function of `message` alone (which must not change during the
// call).

#include <google/protobuf/message.h>

#include <string>

namespace acomms::dccl {

std::string to_json(const google::protobuf::Message& message, bool pretty = false);

}  // namespace acomms::dccl
