// Load-time validation: every rule of the spec's "Load-time validation"
// section, plus .proto syntax errors, reported with message, field and rule.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dccl/codec.h"
#include "test_util.h"

namespace acomms::dccl {
namespace {

using ::testing::HasSubstr;
using testing::error_of;

// Loads body (after the standard header) into a fresh codec and returns the
// load error text ("" if it loaded).
std::string load_error(const std::string& body) {
  testing::TempDir dir;
  Codec codec;
  return error_of([&] { codec.load(dir.write_proto("v.proto", body), {ACOMMS_PROTO_DIR}); });
}

TEST(Validation, GoodMessageLoads) {
  EXPECT_EQ(load_error(R"(message Ok {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 4 };
    required int32 x = 1 [(dccl.field) = { min: 0 max: 10 }];
  })"),
            "");
}

TEST(Validation, MessageOptions) {
  EXPECT_EQ(load_error("message M { option (dccl.msg) = { codec_version: 4 max_bytes: 4 }; }"),
            "t.M: (dccl.msg).id is required unless omit_id is set");
  EXPECT_EQ(load_error("message M { option (dccl.msg) = { codec_version: 4 id: 1 }; }"),
            "t.M: (dccl.msg).max_bytes is required");
  EXPECT_EQ(load_error("message M { option (dccl.msg) = { id: 1 max_bytes: 4 }; }"),
            "t.M: (dccl.msg).codec_version is required");
  EXPECT_EQ(load_error("message M { option (dccl.msg) = { codec_version: 5 id: 1 max_bytes: 4 }; }"),
            "t.M: codec_version 5 is not supported (use 2, 3 or 4)");
  EXPECT_EQ(load_error("message M { option (dccl.msg) = { codec_version: 4 id: 32768 max_bytes: 4 }; }"),
            "t.M: id 32768 is out of range 0..32767");
  EXPECT_EQ(load_error("message M { option (dccl.msg) = { codec_version: 4 omit_id: true max_bytes: 4 }; }"), "");
}

TEST(Validation, NumericBounds) {
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
    required int32 x = 1 [(dccl.field).min = 0];
  })"),
            "t.Bad.x: numeric field needs (dccl.field).min and max");
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
    optional double x = 1 [(dccl.field) = { min: 0 max: 1 precision: 2 resolution: 0.5 }];
  })"),
            "t.Bad.x: precision and resolution are both set");
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
    optional double x = 1 [(dccl.field) = { min: 1 max: 0 }];
  })"),
            "t.Bad.x: max 0 is less than min 1");
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 64 };
    optional double x = 1 [(dccl.field) = { min: 0 max: 1e30 precision: 3 }];
  })"),
            "t.Bad.x: range [min, max] / resolution needs more than 64 bits");
  EXPECT_EQ(load_error(R"(enum E { A = 1; } message Ok {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
    optional E e = 1; optional bool b = 2;
  })"),
            "");  // enums and bools need no bounds
}

TEST(Validation, StringsAndBytesNeedMaxLength) {
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
    optional string s = 1;
    optional bytes b = 2;
  })"),
            "t.Bad.s: string/bytes field needs (dccl.field).max_length\n"
            "t.Bad.b: string/bytes field needs (dccl.field).max_length");
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 2 id: 1 max_bytes: 400 };
    optional string s = 1 [(dccl.field).max_length = 300];
  })"),
            "t.Bad.s: max_length 300 does not fit the 8-bit length of codec_version 2");
}

TEST(Validation, RepeatedNeedsMaxRepeat) {
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
    repeated int32 r = 1 [(dccl.field) = { min: 0 max: 1 }];
  })"),
            "t.Bad.r: repeated field needs (dccl.field).max_repeat");
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
    repeated int32 r = 1 [(dccl.field) = { min: 0 max: 1 min_repeat: 3 max_repeat: 2 }];
  })"),
            "t.Bad.r: max_repeat 2 is less than min_repeat 3");
}

TEST(Validation, HeadFieldsMustBeFixedSize) {
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 16 };
    optional string h = 1 [(dccl.field) = { max_length: 2 in_head: true }];
  })"),
            "t.Bad.h: in_head field must have a fixed size (has 1 to 19 bits)");
  EXPECT_EQ(load_error(R"(message Ok {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 16 };
    optional uint32 h = 1 [(dccl.field) = { min: 0 max: 3 in_head: true }];
  })"),
            "");
}

TEST(Validation, OneofNeedsVersion4) {
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 3 id: 1 max_bytes: 8 };
    oneof choice { bool a = 1; bool b = 2; }
  })"),
            "t.Bad.choice: oneof needs codec_version 4 (message has 3)");
}

TEST(Validation, MaxBytesIsChecked) {
  // id (1 byte) + 17 bits of body (3 bytes) = 4 bytes > 3.
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 3 };
    required uint32 a = 1 [(dccl.field) = { min: 0 max: 131071 }];
  })"),
            "t.Bad: encoded size can reach 4 bytes, more than max_bytes 3");
  // Head and body are padded separately: 8 + 1 head bits -> 2 bytes, 8 body bits -> 1.
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 2 };
    required bool h = 1 [(dccl.field).in_head = true];
    required uint32 b = 2 [(dccl.field) = { min: 0 max: 255 }];
  })"),
            "t.Bad: encoded size can reach 3 bytes, more than max_bytes 2");
}

TEST(Validation, DuplicateIds) {
  EXPECT_EQ(load_error(R"(
    message A { option (dccl.msg) = { codec_version: 4 id: 7 max_bytes: 4 }; }
    message B { option (dccl.msg) = { codec_version: 4 id: 7 max_bytes: 4 }; })"),
            "t.B: DCCL id 7 is already used by t.A");

  testing::TempDir dir;
  Codec codec;
  codec.load(dir.write_proto("a.proto", "message A { option (dccl.msg) = { codec_version: 4 id: 7 max_bytes: 4 }; }"));
  std::string b = dir.write("b.proto",
                            "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage u;\n"
                            "message B { option (dccl.msg) = { codec_version: 4 id: 7 max_bytes: 4 }; }\n");
  EXPECT_EQ(error_of([&] { codec.load(b); }), "u.B: DCCL id 7 is already used by t.A");
  EXPECT_NO_THROW(codec.load(dir.path() + "/a.proto"));  // loading a file again is fine
}

TEST(Validation, UnknownCodecAndBadSpecialCodecs) {
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
    optional int32 x = 1 [(dccl.field) = { codec: "no.such" min: 0 max: 1 }];
  })"),
            "t.Bad.x: unknown field codec \"no.such\"");
  EXPECT_EQ(load_error(R"(message Bad {
    option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
    optional int32 x = 1 [(dccl.field).codec = "dccl.time"];
    optional int32 y = 2 [(dccl.field) = { codec: "dccl.static" static_value: "abc" }];
  })"),
            "t.Bad.x: dccl.time needs a double (seconds) or int64/uint64 (microseconds) field\n"
            "t.Bad.y: static_value \"abc\" is not a valid int32");
}

TEST(Validation, EmbeddedErrorsNameThePath) {
  EXPECT_EQ(load_error(R"(message In { optional int32 v = 1; }
    message Bad {
      option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
      optional In i = 1;
    })"),
            "t.Bad.i.v: numeric field needs (dccl.field).min and max");
  EXPECT_EQ(load_error(R"(message R {
      option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
      optional R again = 1;
    })"),
            "t.R.again: recursive message type t.R is not supported");
}

TEST(Validation, AllErrorsAreReportedAndNothingIsLoaded) {
  testing::TempDir dir;
  Codec codec;
  std::string err = error_of([&] {
    codec.load(dir.write_proto("v.proto", R"(
      message Good { option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 4 }; }
      message Bad1 { option (dccl.msg) = { codec_version: 4 id: 2 }; }
      message Bad2 {
        option (dccl.msg) = { codec_version: 4 id: 3 max_bytes: 8 };
        optional int32 x = 1;
      })"));
  });
  EXPECT_EQ(err, "t.Bad1: (dccl.msg).max_bytes is required\nt.Bad2.x: numeric field needs (dccl.field).min and max");
  EXPECT_EQ(codec.find_type("t.Good"), nullptr);
  EXPECT_TRUE(codec.types().empty());
}

TEST(Validation, SyntaxErrorsGiveFileLineAndColumn) {
  testing::TempDir dir;
  Codec codec;
  std::string file = dir.write_proto("s.proto", "message M {\n  required int32 x = ;\n}\n");
  std::string err = error_of([&] { codec.load(file); });
  EXPECT_THAT(err, HasSubstr(file + ":5:"));
  EXPECT_THAT(err, HasSubstr("Expected field number."));
  try {
    codec.load(file);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::kSchema);
  }
}

TEST(Validation, MissingFilesAndImports) {
  testing::TempDir dir;
  Codec codec;
  EXPECT_THAT(error_of([&] { codec.load(dir.path() + "/nope.proto"); }), HasSubstr("nope.proto"));
  std::string file = dir.write_proto("i.proto", "import \"missing/other.proto\";\n");
  EXPECT_THAT(error_of([&] { codec.load(file); }), HasSubstr("missing/other.proto"));
}

TEST(Validation, ImportsResolveAgainstIncludeDirs) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir.path() + "/lib");
  dir.write("lib/inner.proto",
            "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage lib;\n"
            "message In { required uint32 v = 1 [(dccl.field) = { min: 0 max: 3 }]; }\n");
  std::string top = dir.write("top.proto",
                              "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\n"
                              "import \"lib/inner.proto\";\npackage top;\n"
                              "message M { option (dccl.msg) = { codec_version: 4 id: 9 max_bytes: 4 };\n"
                              "  required lib.In i = 1; }\n");
  Codec codec;
  auto types = codec.load(top, {dir.path(), ACOMMS_PROTO_DIR});
  ASSERT_EQ(types.size(), 1u);
  EXPECT_EQ(types[0]->name, "top.M");
  EXPECT_EQ(types[0]->body.max, 2u);
}

}  // namespace
}  // namespace acomms::dccl
