#pragma once
// DCCL messages to and from JSON, for people and clients: the one place
// both directions live (Submit's and Encode's JSON in, Received's,
// Decode's and the queue listing's JSON out, acommsctl's prompt).
//
// Problem: DCCL messages are proto2 with required fields, and protobuf's
// JSON functions insist on them in both directions. Yet a decoded message
// may lack a required field legitimately ((dccl.field).omit), a Submit may
// leave out the fields the queue's roles fill in (source, time), and a
// message being typed in has its required fields filled last. Decision:
// both directions go through the binary form, which carries partial
// messages; the caller checks completeness where it matters (the codec
// does, on encode).
// Output: proto field names (as in the .proto), fields left at their
// defaults left out, enums by name.
// Thread-safety: message_json and indented_message_json are pure
// functions; a JsonReader may be shared by any threads.

#include <google/protobuf/descriptor.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/message.h>

#include <mutex>
#include <string>

namespace acomms::dccl {

// `message` as one line of JSON (what clients get in a reply's `json`).
std::string message_json(const google::protobuf::Message& message);

// The same JSON, indented over several lines for a person to read.
std::string indented_message_json(const google::protobuf::Message& message);

// Parses JSON into DCCL messages without insisting on their required
// fields: the JSON is parsed into a copy of the type whose fields are all
// optional (kept in the reader's own descriptor pool, one per type), and
// the result carried over in the binary form the two share.
class JsonReader {
 public:
  // Any thread. Returns an empty string on success, else why it failed
  // (malformed JSON, an unknown field by name, a value of the wrong type).
  std::string parse(const std::string& json, google::protobuf::Message* message);

 private:
  const google::protobuf::Descriptor* relaxed(const google::protobuf::Descriptor* type);
  void add_file(const google::protobuf::FileDescriptor* file);

  std::mutex mutex_;
  google::protobuf::DescriptorPool pool_;
  google::protobuf::DynamicMessageFactory factory_{&pool_};
};

}  // namespace acomms::dccl
