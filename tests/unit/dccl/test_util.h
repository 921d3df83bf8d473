// Helpers for the DCCL unit tests: .proto files written to a temporary
// directory, hex conversion, text-format messages.
#pragma once

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "dccl/codec.h"
#include "dccl/hex.h"
#include "temp_dir.h"

namespace acomms::dccl::testing {

// A directory under /tmp removed with the object (tests/support/temp_dir.h),
// with .proto files written into it.
class TempDir : public acomms::testing::TempDir {
 public:
  TempDir() : acomms::testing::TempDir("dccl_unit") {}
  // Writes `name` with the usual proto2 header (package t, DCCL options
  // imported) followed by body; returns its path.
  std::string write_proto(const std::string& name, const std::string& body) const {
    return write(name, "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage t;\n" + body);
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::string file = (*this / name).string();
    std::ofstream(file) << text;
    return file;
  }
  std::string path() const { return string(); }
};

using acomms::dccl::from_hex;
using acomms::dccl::to_hex;

// A message of `type` parsed from text format (test fails on bad text).
inline std::unique_ptr<google::protobuf::Message> make(const Codec& codec, const std::string& type,
                                                       const std::string& text) {
  auto msg = codec.new_message(type);
  google::protobuf::TextFormat::Parser parser;
  parser.AllowPartialMessage(true);  // tests encode messages missing required fields
  EXPECT_TRUE(parser.ParseFromString(text, msg.get())) << text;
  return msg;
}

// Encodes text as `type` and returns hex.
inline std::string encode_hex(const Codec& codec, const std::string& type, const std::string& text) {
  return to_hex(codec.encode(*make(codec, type, text)));
}

// Decodes hex holding exactly one message and returns its short debug string.
inline std::string decode_text(const Codec& codec, const std::string& hex) {
  auto all = codec.decode(from_hex(hex));
  if (all.size() != 1) {
    std::string count("<");  // built stepwise: "<" + string&& trips GCC 12's -Wrestrict
    count += std::to_string(all.size());
    count += " messages>";
    return count;
  }
  return all[0]->ShortDebugString();
}

// The Error message thrown by f, or "" if none.
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace acomms::dccl::testing
