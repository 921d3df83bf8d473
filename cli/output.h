#pragma once
// Printing for people and for scripts. --json output is always one JSON
// object with the API's own field names, so it can be read back with any
// protobuf JSON parser.

#include <google/protobuf/message.h>

#include <cstdint>
#include <string>

namespace acomms::cli {

// An API message (a reply, or part of one) as one line of JSON with proto
// field names and every field printed, defaults too (a zero counter is a
// fact worth showing, not an absent field). DCCL messages a person sent or
// received are printed by dccl::message_json instead (set fields only).
std::string json_with_defaults(const google::protobuf::Message& message);

// json_with_defaults plus a newline on stdout.
void print_json(const google::protobuf::Message& message);

// `text` as a JSON string literal, quotes included.
std::string json_quote(const std::string& text);

// The shortest text that reads back as `value` ("3", "0.1", "1712345678.25").
std::string number_text(double value);

// "3>all", "3>2", "->all": source and destination modem ids as the tables
// show them (a negative id means "not applicable", 0 is broadcast).
std::string route_text(int32_t src, int32_t dest);

// Seconds since the Unix epoch as "2024-04-05T12:34:56.789Z"; "-" for 0.
std::string utc_text(double seconds);

}  // namespace acomms::cli
