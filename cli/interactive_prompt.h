#pragma once
// `send TYPE --interactive`: a message built by answering one question per
// field, with the field's type, DCCL bounds and enum values shown, so a
// person at sea need not have the .proto at hand. Reads plain lines, so it
// works as well with a pipe as with a terminal.

#include <google/protobuf/message.h>

#include <iosfwd>
#include <memory>

namespace acomms::cli {

class TypeSchema;

// Where questions go and answers come from. `echo` repeats each answer on
// `out`: a terminal echoes typing itself, a pipe does not, and without it
// the transcript of a piped run would be questions run together.
struct PromptStreams {
  std::istream& in;
  std::ostream& out;
  bool echo = false;
};

// Asks for every field of the schema's type: an empty answer skips an
// optional field, a bad one is asked again with the reason. UsageError if
// the input ends first.
std::unique_ptr<google::protobuf::Message> prompt_message(TypeSchema& schema, const PromptStreams& streams);

// Shows the message as JSON and asks "send? [y/N]"; true only for y/yes.
bool confirm_send(const google::protobuf::Message& message, const PromptStreams& streams);

}  // namespace acomms::cli
