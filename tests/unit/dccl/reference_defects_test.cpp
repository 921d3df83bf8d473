// Where the reference DCCL's bytes come from a defect or undefined
// behaviour, lenient mode reproduces them (shared/conformance/dccl/
// differences.txt is the conformance test of that) and strict mode refuses
// the input, naming the field, rather than send bytes that decode as
// something else.
#include <gtest/gtest.h>

#include "dccl/codec.h"
#include "test_util.h"

namespace acomms::dccl::testing {
namespace {

class ReferenceDefects : public ::testing::Test {
 protected:
  void SetUp() override {
    codec_.load(dir_.write_proto("d.proto", R"(
message Big {
  option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 16 };
  optional int32 i = 1 [(dccl.field) = { min: -2147483648 max: 2147483647 }];
  optional double d = 2 [(dccl.field) = { min: -10 max: 10 precision: 2 }];
}
message Times {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional double t = 1 [(dccl.field) = { codec: "dccl.time" resolution: 0.5 }];
  optional int64 us = 2 [(dccl.field) = { codec: "dccl.time" resolution: 0.001 }];
  optional int64 ps = 3 [(dccl.field) = { codec: "dccl.time" precision: -3 }];
}
)"));
    codec_.set_clock([] { return 1795464000.0; });
  }

  TempDir dir_;
  Codec codec_;
};

TEST_F(ReferenceDefects, Int32MaxInAWideOptionalFieldArrivesAsNotSetUnlessStrict) {
  EXPECT_EQ(decode_text(codec_, encode_hex(codec_, "t.Big", "i: 2147483647")), "");
  EXPECT_EQ(decode_text(codec_, encode_hex(codec_, "t.Big", "i: 2147483646")), "i: 2147483646");
  EXPECT_EQ(decode_text(codec_, encode_hex(codec_, "t.Big", "i: 0")), "i: 0");
  codec_.set_strict(true);
  EXPECT_EQ(error_of([&] { encode_hex(codec_, "t.Big", "i: 2147483647"); }),
            "t.Big.i: value 2147483647 would arrive as not set (value - min overflows the field's type in the "
            "reference DCCL)");
  EXPECT_EQ(decode_text(codec_, encode_hex(codec_, "t.Big", "i: 0")), "i: 0");
}

TEST_F(ReferenceDefects, NanArrivesAsMinUnlessStrict) {
  EXPECT_EQ(decode_text(codec_, encode_hex(codec_, "t.Big", "d: nan")), "d: -10");
  codec_.set_strict(true);
  EXPECT_EQ(error_of([&] { encode_hex(codec_, "t.Big", "d: nan"); }), "t.Big.d: value nan out of range [-10, 10]");
}

// fmod of a negative time is negative: out of range, all zeros (an optional
// field then arrives as not set, a required one as the start of the window).
TEST_F(ReferenceDefects, NegativeTimeIsSentAsZerosUnlessStrict) {
  EXPECT_EQ(encode_hex(codec_, "t.Times", "t: -1.5"), encode_hex(codec_, "t.Times", ""));
  codec_.set_strict(true);
  EXPECT_EQ(error_of([&] { encode_hex(codec_, "t.Times", "t: -1.5"); }), "t.Times.t: value -1.5 out of range [0, 86400]");
}

TEST_F(ReferenceDefects, MicrosecondTimeResolutionIsInSecondsAndPrecisionInMicroseconds) {
  const TypeInfo* info = codec_.find_type("t.Times");
  ASSERT_NE(info, nullptr);
  ASSERT_EQ(info->fields.size(), 3u);
  EXPECT_EQ(info->fields[1].bits.max, 27u);  // 86,400,000 ms steps + not set
  EXPECT_EQ(info->fields[2].bits.max, 27u);  // precision -3: 10^3 us = 1 ms
  EXPECT_DOUBLE_EQ(info->fields[1].resolution, 1000.0);  // in the field's unit, us
  // Half a step of a microsecond time rounds as its double seconds value
  // does (1795432605.0005 s is 1795432605.000499964 as a double): down.
  EXPECT_EQ(decode_text(codec_, encode_hex(codec_, "t.Times", "ps: 1795432605000500")), "ps: 1795432605000000");
}

TEST_F(ReferenceDefects, DoubleTimeWithAResolutionDecodesToWholeSeconds) {
  EXPECT_EQ(decode_text(codec_, encode_hex(codec_, "t.Times", "t: 1795478401.5")), "t: 1795478402");
}

}  // namespace
}  // namespace acomms::dccl::testing
