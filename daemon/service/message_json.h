#pragma once
// Messages to and from JSON for clients (to_json: see dccl/message_json.h).

#include <google/protobuf/descriptor.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/message.h>

#include <mutex>
#include <string>

#include "dccl/message_json.h"

namespace acomms::service {

using dccl::to_json;

// Parses JSON into DCCL messages without insisting on their required
// fields: a Submit may leave out the fields the queue's roles fill in
// (source, time), and the caller checks the rest afterwards. protobuf's JSON
// parser rejects a message with a required field missing, so the JSON is
// parsed into a copy of the type whose fields are all optional, and the
// result carried over in the binary form the two share.
class JsonReader {
 public:
  // Any thread. Returns an empty string on success, else why it failed.
  std::string parse(const std::string& json, google::protobuf::Message* message);

 private:
  const google::protobuf::Descriptor* relaxed(const google::protobuf::Descriptor* type);
  void add_file(const google::protobuf::FileDescriptor* file);

  std::mutex mutex_;
  google::protobuf::DescriptorPool pool_;
  google::protobuf::DynamicMessageFactory factory_{&pool_};
};

}  // namespace acomms::service
