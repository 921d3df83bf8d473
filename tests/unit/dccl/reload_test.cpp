// Loading a file again: after a failed load the corrected file must load (an
// operator fixes a bound and retries), an unchanged file loads again
// harmlessly, and a file that changed after it was loaded is refused by name
// rather than silently kept in its old form.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dccl/codec.h"
#include "test_util.h"

namespace acomms::dccl {
namespace {

using ::testing::HasSubstr;
using testing::error_of;

constexpr const char* kMissingBounds = R"(message Fix {
  option (dccl.msg) = { codec_version: 4 id: 5 max_bytes: 8 };
  required int32 x = 1;
})";
constexpr const char* kFixed = R"(message Fix {
  option (dccl.msg) = { codec_version: 4 id: 5 max_bytes: 8 };
  required int32 x = 1 [(dccl.field) = { min: 0 max: 100 }];
})";

TEST(Reload, FileCorrectedAfterADcclRuleErrorLoads) {
  testing::TempDir dir;
  Codec codec;
  std::string file = dir.write_proto("fix.proto", kMissingBounds);
  EXPECT_EQ(error_of([&] { codec.load(file, {ACOMMS_PROTO_DIR}); }),
            "t.Fix.x: numeric field needs (dccl.field).min and max");
  dir.write_proto("fix.proto", kFixed);
  auto types = codec.load(file, {ACOMMS_PROTO_DIR});
  ASSERT_EQ(types.size(), 1u);
  EXPECT_EQ(types[0]->name, "t.Fix");
  // The codec uses the corrected definition: 100 is in range and round-trips.
  auto msg = testing::make(codec, "t.Fix", "x: 100");
  auto decoded = codec.decode(codec.encode(*msg));
  ASSERT_EQ(decoded.size(), 1u);
  EXPECT_EQ(decoded[0]->ShortDebugString(), "x: 100");
}

TEST(Reload, FileCorrectedAfterAnIdClashLoads) {
  testing::TempDir dir;
  Codec codec;
  codec.load(dir.write_proto("first.proto", R"(message First {
    option (dccl.msg) = { codec_version: 4 id: 5 max_bytes: 4 };
  })"), {ACOMMS_PROTO_DIR});
  std::string file = dir.write_proto("fix.proto", kFixed);
  EXPECT_EQ(error_of([&] { codec.load(file); }), "t.Fix: DCCL id 5 is already used by t.First");
  dir.write_proto("fix.proto", R"(message Fix {
    option (dccl.msg) = { codec_version: 4 id: 6 max_bytes: 8 };
    required int32 x = 1 [(dccl.field) = { min: 0 max: 100 }];
  })");
  auto types = codec.load(file);
  ASSERT_EQ(types.size(), 1u);
  EXPECT_EQ(types[0]->id, 6);
  EXPECT_EQ(codec.find_id(6)->name, "t.Fix");
}

TEST(Reload, FileCorrectedAfterASyntaxErrorLoads) {
  testing::TempDir dir;
  Codec codec;
  std::string file = dir.write_proto("fix.proto", "message Fix {\n  required int32 x = ;\n}\n");
  EXPECT_THAT(error_of([&] { codec.load(file, {ACOMMS_PROTO_DIR}); }), HasSubstr("Expected field number."));
  dir.write_proto("fix.proto", kFixed);
  EXPECT_EQ(codec.load(file).size(), 1u);
}

TEST(Reload, UnchangedFileLoadsAgainAndGivesTheSameTypes) {
  testing::TempDir dir;
  Codec codec;
  std::string file = dir.write_proto("same.proto", kFixed);
  auto first = codec.load(file, {ACOMMS_PROTO_DIR});
  // Comments and layout are not definitions: touching them changes nothing.
  dir.write_proto("same.proto", std::string("// reviewed\n") + kFixed);
  auto again = codec.load(file);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0], first[0]);
  EXPECT_EQ(codec.types().size(), 1u);
}

TEST(Reload, ChangedFileIsRefusedAndTheLoadedVersionStays) {
  testing::TempDir dir;
  Codec codec;
  std::string file = dir.write_proto("moved.proto", kFixed);
  codec.load(file, {ACOMMS_PROTO_DIR});
  dir.write_proto("moved.proto", R"(message Fix {
    option (dccl.msg) = { codec_version: 4 id: 5 max_bytes: 8 };
    required int32 x = 1 [(dccl.field) = { min: 0 max: 1000 }];
  })");
  std::string err = error_of([&] { codec.load(file); });
  EXPECT_THAT(err, HasSubstr("moved.proto"));
  EXPECT_THAT(err, HasSubstr("changed since it was loaded"));
  EXPECT_THAT(err, HasSubstr("or restart to use it"));
  // Still the first version: 1000 is out of its range.
  EXPECT_EQ(codec.find_type("t.Fix")->fields.size(), 1u);
  codec.set_strict(true);
  EXPECT_THAT(error_of([&] { codec.encode(*testing::make(codec, "t.Fix", "x: 1000")); }), HasSubstr("100"));
}

TEST(Reload, ChangedImportIsRefusedByName) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir.path() + "/lib");
  const std::string inner_header = "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage lib;\n";
  dir.write("lib/inner.proto", inner_header + "message In { required uint32 v = 1 [(dccl.field) = { min: 0 max: 3 }]; }\n");
  const std::string top_text =
      "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\nimport \"lib/inner.proto\";\npackage top;\n"
      "message A { option (dccl.msg) = { codec_version: 4 id: 9 max_bytes: 4 };\n  required lib.In i = 1; }\n";
  Codec codec;
  codec.load(dir.write("a.proto", top_text), {dir.path(), ACOMMS_PROTO_DIR});
  dir.write("lib/inner.proto", inner_header + "message In { required uint32 v = 1 [(dccl.field) = { min: 0 max: 7 }]; }\n");
  std::string b = dir.write("b.proto",
                            "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\n"
                            "import \"lib/inner.proto\";\npackage top;\n"
                            "message B { option (dccl.msg) = { codec_version: 4 id: 10 max_bytes: 4 };\n"
                            "  required lib.In i = 1; }\n");
  std::string err = error_of([&] { codec.load(b); });
  EXPECT_THAT(err, HasSubstr("lib/inner.proto"));
  EXPECT_THAT(err, HasSubstr("changed since it was loaded"));
  EXPECT_EQ(codec.find_type("top.B"), nullptr);
}

}  // namespace
}  // namespace acomms::dccl
