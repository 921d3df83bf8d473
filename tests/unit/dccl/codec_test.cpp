// Encoding rules and quirks of the DCCL codec, each checked on bytes and on
// decoded values.
#include "dccl/codec.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "test_util.h"

namespace acomms::dccl {
namespace {

using ::testing::HasSubstr;
using testing::decode_text;
using testing::encode_hex;
using testing::error_of;
using testing::from_hex;
using testing::make;
using testing::to_hex;

constexpr const char* kProto = R"(
message Opt2 {
  option (dccl.msg) = { codec_version: 2 id: 2 max_bytes: 8 };
  optional uint32 a = 1 [(dccl.field) = { min: 0 max: 6 }];   // 3 bits, 0 = not set
  required uint32 b = 2 [(dccl.field) = { min: 0 max: 7 }];   // 3 bits
}
message Opt3 {
  option (dccl.msg) = { codec_version: 3 id: 3 max_bytes: 8 };
  optional uint32 a = 1 [(dccl.field) = { min: 0 max: 6 }];
  required uint32 b = 2 [(dccl.field) = { min: 0 max: 7 }];
  repeated uint32 r = 3 [(dccl.field) = { min: 0 max: 7 max_repeat: 2 }];  // 2-bit count, 3-bit elements
}
message Num {
  option (dccl.msg) = { codec_version: 4 id: 10 max_bytes: 32 };
  required int32 ri = 1 [(dccl.field) = { min: -100 max: 100 }];
  optional double od = 2 [(dccl.field) = { min: -10 max: 10 precision: 2 }];
  optional int32 neg = 3 [(dccl.field) = { min: -100 max: 100 precision: -1 }];
  optional float f = 4 [(dccl.field) = { min: 0 max: 0.07 precision: 2 }];
  optional int64 big = 5 [(dccl.field) = { min: -9e18 max: 9e18 }];
  optional uint64 ubig = 6 [(dccl.field) = { min: 0 max: 1.8e19 }];
}
message S2 {
  option (dccl.msg) = { codec_version: 2 id: 20 max_bytes: 32 };
  optional string s = 1 [(dccl.field).max_length = 4];
}
message S3 {
  option (dccl.msg) = { codec_version: 3 id: 21 max_bytes: 32 };
  optional string s = 1 [(dccl.field).max_length = 4];
}
message S4 {
  option (dccl.msg) = { codec_version: 4 id: 22 max_bytes: 32 };
  optional string s = 1 [(dccl.field).max_length = 4];
  optional bytes b = 2 [(dccl.field) = { max_length: 2 codec: "dccl.var_bytes" }];
}
message Rep {
  option (dccl.msg) = { codec_version: 4 id: 30 max_bytes: 32 };
  repeated int32 a = 1 [(dccl.field) = { min: 0 max: 15 min_repeat: 2 max_repeat: 4 }];
}
message One {
  option (dccl.msg) = { codec_version: 4 id: 31 max_bytes: 8 };
  oneof c {
    uint32 x = 1 [(dccl.field) = { min: 0 max: 3 }];
    bool y = 2;
  }
  required uint32 z = 3 [(dccl.field) = { min: 0 max: 1 }];
}
message Pres {
  option (dccl.msg) = { codec_version: 4 id: 32 max_bytes: 8 };
  optional int32 p = 1 [(dccl.field) = { codec: "dccl.presence" min: -100 max: 100 }];
  optional int32 q = 2 [(dccl.field) = { min: -100 max: 100 }];
}
message Stat {
  option (dccl.msg) = { codec_version: 4 id: 33 max_bytes: 8 };
  required string s = 1 [(dccl.field) = { codec: "dccl.static" static_value: "hi" }];
  required int32 n = 2 [(dccl.field) = { codec: "dccl.static" static_value: "42" }];
  required uint32 v = 3 [(dccl.field) = { min: 0 max: 255 }];
}
message Time {
  option (dccl.msg) = { codec_version: 4 id: 34 max_bytes: 32 };
  required double t = 1 [(dccl.field).codec = "dccl.time"];
  optional int64 us = 2 [(dccl.field).codec = "dccl.time"];
  optional uint64 ms = 3 [(dccl.field) = { codec: "dccl.time" precision: -3 num_days: 2 }];
}
message Head {
  option (dccl.msg) = { codec_version: 4 id: 35 max_bytes: 16 };
  required uint32 h = 1 [(dccl.field) = { min: 0 max: 255 in_head: true }];
  required uint32 b = 2 [(dccl.field) = { min: 0 max: 255 }];
  optional string s = 3 [(dccl.field).max_length = 8];
}
message Big {
  option (dccl.msg) = { codec_version: 4 id: 300 max_bytes: 4 };
}
message Inner { optional uint32 v = 1 [(dccl.field) = { min: 0 max: 6 }]; }
message Emb2 {
  option (dccl.msg) = { codec_version: 2 id: 36 max_bytes: 8 };
  optional Inner o = 1;
}
)";

class CodecTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new testing::TempDir;
    codec_ = new Codec;
    codec_->load(dir_->write_proto("t.proto", kProto), {ACOMMS_PROTO_DIR});
  }
  static void TearDownTestSuite() {
    delete codec_;
    delete dir_;
  }
  void SetUp() override {
    codec_->set_strict(false);
    codec_->clear_crypto();
    codec_->set_clock(nullptr);
  }
  static Codec& codec() { return *codec_; }
  // Encode then decode; returns the decoded message as text.
  static std::string round_trip(const std::string& type, const std::string& text) {
    return decode_text(codec(), encode_hex(codec(), type, text));
  }

  static testing::TempDir* dir_;
  static Codec* codec_;
};
testing::TempDir* CodecTest::dir_ = nullptr;
Codec* CodecTest::codec_ = nullptr;

// ------------------------------------------------------------------ ids

TEST_F(CodecTest, OneAndTwoByteIds) {
  EXPECT_EQ(encode_hex(codec(), "t.Big", ""), "5902");  // (300 << 1) | 1 little-endian
  EXPECT_EQ(codec().id_of(from_hex("5902")), 300);
  EXPECT_EQ(codec().id_of(from_hex("04ff")), 2);
  EXPECT_EQ(decode_text(codec(), "5902"), "");
  EXPECT_EQ(codec().find_id(300)->name, "t.Big");
  EXPECT_EQ(codec().find_type("t.Big")->id_bits, 16u);
}

// ------------------------------------------------------------------ required / optional

TEST_F(CodecTest, OptionalValuesAreShiftedByOne) {
  EXPECT_EQ(encode_hex(codec(), "t.Opt2", "a: 0 b: 7"), "0439");  // a -> 1, b -> 7 at bit 3
  EXPECT_EQ(encode_hex(codec(), "t.Opt2", "b: 0"), "0400");       // a unset -> 0
  EXPECT_EQ(decode_text(codec(), "0400"), "b: 0");
  EXPECT_EQ(decode_text(codec(), "0439"), "a: 0 b: 7");
}

TEST_F(CodecTest, V3RepeatedElementsUseRequiredEncoding) {
  // a=0 -> 1 (3 bits), b=7, count 1 (2 bits), r[0]=5 unshifted (3 bits)
  EXPECT_EQ(encode_hex(codec(), "t.Opt3", "a: 0 b: 7 r: 5"), "067905");
  EXPECT_EQ(decode_text(codec(), "067905"), "a: 0 b: 7 r: 5");
}

TEST_F(CodecTest, V2OptionalMessageWritesAllFieldsAndDecodesEmptyAsUnset) {
  EXPECT_EQ(encode_hex(codec(), "t.Emb2", ""), "4800");
  EXPECT_EQ(encode_hex(codec(), "t.Emb2", "o { v: 2 }"), "4803");
  EXPECT_EQ(decode_text(codec(), "4800"), "");
  EXPECT_EQ(decode_text(codec(), "4803"), "o { v: 2 }");
}

// ------------------------------------------------------------------ numbers

TEST_F(CodecTest, RoundHalfUpOnTheBinaryDouble) {
  EXPECT_EQ(round_trip("t.Num", "ri: 1 od: 1.005"), "ri: 1 od: 1");      // 1.005 is below 1.005
  EXPECT_EQ(round_trip("t.Num", "ri: 1 od: -0.125"), "ri: 1 od: -0.12");  // -12.5 -> -12
  EXPECT_EQ(round_trip("t.Num", "ri: 1 od: 0.125"), "ri: 1 od: 0.13");
  EXPECT_EQ(round_trip("t.Num", "ri: 1 od: 9.999"), "ri: 1 od: 10");
}

TEST_F(CodecTest, IntegerResolutionAboveOneRoundsLikeTruncatingRemainder) {
  EXPECT_EQ(round_trip("t.Num", "ri: 0 neg: 5"), "ri: 0 neg: 10");     // half up
  EXPECT_EQ(round_trip("t.Num", "ri: 0 neg: 14"), "ri: 0 neg: 10");
  EXPECT_EQ(round_trip("t.Num", "ri: 0 neg: 15"), "ri: 0 neg: 20");
  EXPECT_EQ(round_trip("t.Num", "ri: 0 neg: -8"), "ri: 0 neg: 0");     // negatives toward zero
  EXPECT_EQ(round_trip("t.Num", "ri: 0 neg: -15"), "ri: 0 neg: -10");
  EXPECT_EQ(round_trip("t.Num", "ri: 0 neg: -19"), "ri: 0 neg: -10");
}

TEST_F(CodecTest, FloatIsQuantisedInFloat) {
  // 0.07f quantises to 0.07f > 0.07 (double): out of range, sent as "not set".
  EXPECT_EQ(round_trip("t.Num", "ri: 0 f: 0.07"), "ri: 0");
  EXPECT_EQ(round_trip("t.Num", "ri: 0 f: 0.06"), "ri: 0 f: 0.06");
  codec().set_strict(true);
  EXPECT_THAT(error_of([&] { encode_hex(codec(), "t.Num", "ri: 0 f: 0.07"); }),
              HasSubstr("t.Num.f: value 0.07"));
}

TEST_F(CodecTest, OutOfRangeIsZeros) {
  EXPECT_EQ(encode_hex(codec(), "t.Num", "ri: 101 od: 10.01 neg: 105"),
            encode_hex(codec(), "t.Num", "ri: -100"));
  EXPECT_EQ(round_trip("t.Num", "ri: 101 od: -11"), "ri: -100");  // required decodes as min
}

TEST_F(CodecTest, SixtyFourBitRanges) {
  EXPECT_EQ(codec().find_type("t.Num")->body.max, 8u + 11 + 5 + 4 + 64 + 64);
  EXPECT_EQ(round_trip("t.Num", "ri: 0 big: -9000000000000000000"), "ri: 0 big: -9000000000000000000");
  EXPECT_EQ(round_trip("t.Num", "ri: 0 big: 9000000000000000000"), "ri: 0 big: 9000000000000000000");
  EXPECT_EQ(round_trip("t.Num", "ri: 0 big: -9223372036854775808"), "ri: 0");
  EXPECT_EQ(round_trip("t.Num", "ri: 0 ubig: 18000000000000000000"), "ri: 0 ubig: 18000000000000000000");
  EXPECT_EQ(round_trip("t.Num", "ri: 0 ubig: 18446744073709551615"), "ri: 0");
}

// NaN passes the reference's range check and becomes wire value 2^63 (+1
// when optional) cut to the field's bits: an optional field decodes as min.
// Strict mode refuses it.
TEST_F(CodecTest, NanIsEncodedAsTheReferenceDoesAndInfinityIsOutOfRange) {
  EXPECT_EQ(round_trip("t.Num", "ri: 0 od: nan"), "ri: 0 od: -10");
  EXPECT_EQ(round_trip("t.Num", "ri: 0 od: inf f: -inf"), "ri: 0");
  codec().set_strict(true);
  EXPECT_EQ(error_of([&] { encode_hex(codec(), "t.Num", "ri: 0 od: nan"); }),
            "t.Num.od: value nan out of range [-10, 10]");
}

// ------------------------------------------------------------------ strings

TEST_F(CodecTest, StringsPerVersion) {
  EXPECT_EQ(encode_hex(codec(), "t.S2", "s: \"\""), "2800");  // v2: 8-bit length 0 = not set
  EXPECT_EQ(encode_hex(codec(), "t.S2", "s: \"ab\""), "28026162");
  EXPECT_EQ(decode_text(codec(), "2800"), "");
  EXPECT_EQ(encode_hex(codec(), "t.S3", "s: \"\""), "2a00");  // v3: 3-bit length 0 = not set
  EXPECT_EQ(encode_hex(codec(), "t.S3", "s: \"ab\""), "2a0a1303");
  EXPECT_EQ(decode_text(codec(), "2a00"), "");
  EXPECT_EQ(decode_text(codec(), "2a0a1303"), "s: \"ab\"");
  EXPECT_EQ(encode_hex(codec(), "t.S4", ""), "2c00");         // v4: presence bit
  EXPECT_EQ(encode_hex(codec(), "t.S4", "s: \"\""), "2c01");
  EXPECT_EQ(decode_text(codec(), "2c01"), "s: \"\"");
}

TEST_F(CodecTest, LongStringsAreTruncated) {
  EXPECT_EQ(encode_hex(codec(), "t.S2", "s: \"abcdef\""), "280461626364");
  EXPECT_EQ(round_trip("t.S4", "s: \"abcdef\" b: \"xyz\""), "s: \"abcd\" b: \"xy\"");
  codec().set_strict(true);
  EXPECT_EQ(error_of([&] { encode_hex(codec(), "t.S2", "s: \"abcdef\""); }),
            "t.S2.s: length 6 exceeds max_length 4");
  EXPECT_EQ(error_of([&] { encode_hex(codec(), "t.S4", "b: \"xyz\""); }), "t.S4.b: length 3 exceeds max_length 2");
}

// ------------------------------------------------------------------ repeated, oneof, presence, static

TEST_F(CodecTest, RepeatedCountPrefixPaddingAndTruncation) {
  EXPECT_EQ(encode_hex(codec(), "t.Rep", ""), "3c0000");  // count 2 (prefix 0) + 2 zero elements
  EXPECT_EQ(decode_text(codec(), "3c0000"), "a: 0 a: 0");
  EXPECT_EQ(round_trip("t.Rep", "a: 1 a: 2 a: 3"), "a: 1 a: 2 a: 3");
  EXPECT_EQ(round_trip("t.Rep", "a: 1 a: 2 a: 3 a: 4 a: 5"), "a: 1 a: 2 a: 3 a: 4");
  codec().set_strict(true);
  EXPECT_EQ(error_of([&] { encode_hex(codec(), "t.Rep", "a: 1 a: 2 a: 3 a: 4 a: 5"); }),
            "t.Rep.a: 5 elements exceed max_repeat 4");
}

TEST_F(CodecTest, OneofSelectorComesFirst) {
  EXPECT_EQ(encode_hex(codec(), "t.One", "y: true z: 1"), "3e0e");  // selector 2, y 1, z 1
  EXPECT_EQ(encode_hex(codec(), "t.One", "x: 3 z: 0"), "3e0d");     // selector 1, x 3, z 0
  EXPECT_EQ(encode_hex(codec(), "t.One", "z: 1"), "3e04");          // selector 0
  EXPECT_EQ(decode_text(codec(), "3e0e"), "y: true z: 1");
  EXPECT_EQ(decode_text(codec(), "3e0d"), "x: 3 z: 0");
  EXPECT_EQ(decode_text(codec(), "3e07"), "z: 1");  // selector 3 names no member
}

TEST_F(CodecTest, PresenceCodecPerField) {
  EXPECT_EQ(encode_hex(codec(), "t.Pres", ""), "400000");          // 1 bit + 8 bits
  EXPECT_EQ(encode_hex(codec(), "t.Pres", "p: -100 q: -100"), "40010200");
  EXPECT_EQ(decode_text(codec(), "40010200"), "p: -100 q: -100");
  EXPECT_EQ(codec().find_type("t.Pres")->fields[0].codec, "dccl.presence");
}

TEST_F(CodecTest, StaticFieldsTakeNoBits) {
  EXPECT_EQ(encode_hex(codec(), "t.Stat", "s: \"other\" n: 1 v: 7"), "4207");
  EXPECT_EQ(decode_text(codec(), "4207"), "s: \"hi\" n: 42 v: 7");
}

// ------------------------------------------------------------------ time

TEST_F(CodecTest, TimePicksTheWindowNearestTheClock) {
  const double t = 1700000000;  // 80000 s into its UTC day
  std::string hex = encode_hex(codec(), "t.Time", "t: 1700000000.4 us: 1700000000600000");
  auto decode_at = [&](double now) {
    codec().set_clock([now] { return now; });
    return decode_text(codec(), hex);
  };
  EXPECT_EQ(decode_at(t), "t: 1700000000 us: 1700000001000000");
  EXPECT_EQ(decode_at(t + 40000), "t: 1700000000 us: 1700000001000000");  // next day, still within 12 h
  EXPECT_EQ(decode_at(t - 40000), "t: 1700000000 us: 1700000001000000");
  EXPECT_EQ(decode_at(t + 50000), "t: 1700086400 us: 1700086401000000");  // nearer the next day's copy
  EXPECT_EQ(decode_at(t - 50000), "t: 1699913600 us: 1699913601000000");
}

TEST_F(CodecTest, TimeWithPrecisionAndSeveralDays) {
  codec().set_clock([] { return 1700000000.0; });
  // ms resolution, 2-day window
  EXPECT_EQ(round_trip("t.Time", "t: 1700000000 ms: 1700000100123456"), "t: 1700000000 ms: 1700000100123000");
  EXPECT_EQ(round_trip("t.Time", "t: 1700000000 ms: 1700080000123999"), "t: 1700000000 ms: 1700080000124000");
  EXPECT_EQ(round_trip("t.Time", "t: 1700000000 ms: 1699920000000000"), "t: 1700000000 ms: 1699920000000000");
}

// ------------------------------------------------------------------ head and encryption

TEST_F(CodecTest, HeadFieldsFollowTheId) {
  EXPECT_EQ(encode_hex(codec(), "t.Head", "h: 1 b: 2"), "46010200");
  EXPECT_EQ(decode_text(codec(), "46010200"), "h: 1 b: 2");
}

TEST_F(CodecTest, EncryptionKeepsHeadClearAndRoundTrips) {
  std::string plain = encode_hex(codec(), "t.Head", "h: 1 b: 2 s: \"secret\"");
  codec().set_crypto("passphrase");
  std::string secret = encode_hex(codec(), "t.Head", "h: 1 b: 2 s: \"secret\"");
  EXPECT_EQ(secret.size(), plain.size());
  EXPECT_EQ(secret.substr(0, 4), "4601");  // id and in_head field in clear
  EXPECT_NE(secret, plain);
  EXPECT_EQ(decode_text(codec(), secret), "h: 1 b: 2 s: \"secret\"");
  // Another head gives another key stream.
  std::string other = encode_hex(codec(), "t.Head", "h: 2 b: 2 s: \"secret\"");
  EXPECT_NE(other.substr(4), secret.substr(4));
}

TEST_F(CodecTest, EmptyPassphraseStillEncryptsAndExemptIdsDoNot) {
  std::string plain = encode_hex(codec(), "t.Head", "h: 1 b: 2 s: \"secret\"");
  codec().set_crypto("");
  EXPECT_NE(encode_hex(codec(), "t.Head", "h: 1 b: 2 s: \"secret\""), plain);
  codec().set_crypto("x", {35});
  EXPECT_EQ(encode_hex(codec(), "t.Head", "h: 1 b: 2 s: \"secret\""), plain);
}

TEST_F(CodecTest, EncryptedMessagesBackToBack) {
  codec().set_crypto("k");
  std::string a = codec().encode(*make(codec(), "t.Head", "h: 1 b: 2 s: \"x\""));
  std::string b = codec().encode(*make(codec(), "t.Opt2", "a: 3 b: 4"));
  auto all = codec().decode(a + b + a);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0]->ShortDebugString(), "h: 1 b: 2 s: \"x\"");
  EXPECT_EQ(all[1]->ShortDebugString(), "a: 3 b: 4");
  EXPECT_EQ(all[2]->ShortDebugString(), "h: 1 b: 2 s: \"x\"");
}

// ------------------------------------------------------------------ several messages, foreign messages

TEST_F(CodecTest, DecodesConcatenatedMessagesOfDifferentTypes) {
  std::string bytes = codec().encode(*make(codec(), "t.Opt2", "b: 1")) +
                      codec().encode(*make(codec(), "t.Big", "")) +
                      codec().encode(*make(codec(), "t.S4", "s: \"q\""));
  auto all = codec().decode(bytes);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0]->GetDescriptor()->full_name(), "t.Opt2");
  EXPECT_EQ(all[1]->GetDescriptor()->full_name(), "t.Big");
  EXPECT_EQ(all[2]->ShortDebugString(), "s: \"q\"");
  EXPECT_TRUE(codec().decode("").empty());
}

TEST_F(CodecTest, EncodesSameTypeFromAnotherPool) {
  Codec other;
  other.load(dir_->path() + "/t.proto", {ACOMMS_PROTO_DIR});
  auto msg = make(other, "t.Opt2", "a: 0 b: 7");
  EXPECT_EQ(to_hex(codec().encode(*msg)), "0439");
}

TEST_F(CodecTest, DecodeAsChecksTheId) {
  EXPECT_EQ(codec().decode_as("t.Opt2", from_hex("0439"))->ShortDebugString(), "a: 0 b: 7");
  EXPECT_EQ(error_of([&] { codec().decode_as("t.S2", from_hex("0439")); }),
            "DCCL id 2 is not t.S2 (id 20)");
}

// ------------------------------------------------------------------ strict mode

TEST_F(CodecTest, StrictModeRejectsWhatDefaultModeFixes) {
  EXPECT_NO_THROW(encode_hex(codec(), "t.Num", "ri: 1000"));
  EXPECT_NO_THROW(encode_hex(codec(), "t.Opt2", "a: 1"));  // b missing: encoded as 0
  codec().set_strict(true);
  EXPECT_EQ(error_of([&] { encode_hex(codec(), "t.Num", "ri: 1000"); }),
            "t.Num.ri: value 1000 out of range [-100, 100]");
  EXPECT_EQ(error_of([&] { encode_hex(codec(), "t.Num", "ri: 0 neg: 105"); }),
            "t.Num.neg: value 105 out of range [-100, 100]");
  EXPECT_EQ(error_of([&] { encode_hex(codec(), "t.Opt2", "a: 1"); }), "t.Opt2.b: required field is not set");
  EXPECT_EQ(encode_hex(codec(), "t.Num", "ri: 100"), encode_hex(codec(), "t.Num", "ri: 100"));
}

// ------------------------------------------------------------------ bad input

TEST_F(CodecTest, TruncatedInputNamesFieldAndBit) {
  EXPECT_EQ(error_of([&] { codec().decode(from_hex("1465")); }),
            "t.Num.od: message truncated at bit 16 (needs 11 bits, 0 left)");
  EXPECT_EQ(error_of([&] { codec().decode(from_hex("14")); }),
            "t.Num.ri: message truncated at bit 8 (needs 8 bits, 0 left)");
  EXPECT_EQ(error_of([&] { codec().decode(from_hex("2804616263")); }),
            "t.S2.s: message truncated at bit 16 (needs 32 bits, 24 left)");
  EXPECT_EQ(error_of([&] { codec().decode(from_hex("0439" "14")); }),
            "t.Num.ri: message truncated at bit 8 (needs 8 bits, 0 left)");
}

TEST_F(CodecTest, UnknownAndTruncatedIds) {
  EXPECT_EQ(error_of([&] { codec().decode(from_hex("9a00")); }), "unknown DCCL id 77");
  EXPECT_EQ(error_of([&] { codec().decode(from_hex("01")); }), "message truncated in the DCCL id");
  EXPECT_EQ(error_of([&] { codec().id_of(""); }), "message truncated in the DCCL id");
  try {
    codec().decode(from_hex("9a"));
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::kDecode);
  }
}

TEST_F(CodecTest, GarbageNeverCrashes) {
  std::mt19937 rng(12345);
  std::vector<int> ids;
  for (const TypeInfo* t : codec().types()) ids.push_back(t->id);
  for (bool crypto : {false, true}) {
    if (crypto) codec().set_crypto("k");
    for (int i = 0; i < 20000; ++i) {
      std::string bytes(rng() % 24, '\0');
      for (char& c : bytes) c = static_cast<char>(rng());
      if (!bytes.empty() && i % 2 == 0) {
        int id = ids[rng() % ids.size()];
        std::string head;
        if (id < 128) {
          head = std::string(1, static_cast<char>(id << 1));
        } else {
          head = {static_cast<char>(((id << 1) | 1) & 0xff), static_cast<char>(id >> 7)};
        }
        bytes = head + bytes;
      }
      try {
        codec().decode(bytes);
      } catch (const Error&) {
      }
    }
  }
}

// ------------------------------------------------------------------ type info

TEST_F(CodecTest, TypeInfoGivesSizesAndFieldBudget) {
  const TypeInfo* info = codec().find_type("t.Head");
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->id, 35);
  EXPECT_EQ(info->codec_version, 4);
  EXPECT_EQ(info->head.max, 8u);
  EXPECT_EQ(info->body.min, 9u);             // b + presence bit
  EXPECT_EQ(info->body.max, 8u + 1 + 4 + 64);
  EXPECT_EQ(info->min_size_bytes(), 4u);
  EXPECT_EQ(info->max_size_bytes(), 2u + 10);
  ASSERT_EQ(info->fields.size(), 3u);
  EXPECT_EQ(info->fields[0].path, "t.Head.h");
  EXPECT_TRUE(info->fields[0].in_head);
  EXPECT_EQ(info->fields[1].codec, "_default4");
  EXPECT_DOUBLE_EQ(codec().find_type("t.Num")->fields[1].resolution, 0.01);

  const TypeInfo* emb = codec().find_type("t.Emb2");
  ASSERT_EQ(emb->fields.size(), 2u);
  EXPECT_EQ(emb->fields[1].path, "t.Emb2.o.v");
  EXPECT_EQ(emb->fields[1].depth, 1);
}

TEST_F(CodecTest, NewMessageOfUnknownTypeThrows) {
  EXPECT_EQ(error_of([&] { codec().new_message("t.Nope"); }), "DCCL type t.Nope is not loaded");
  EXPECT_EQ(codec().find_type("t.Inner"), nullptr);  // no (dccl.msg): embeddable only
}

}  // namespace
}  // namespace acomms::dccl
