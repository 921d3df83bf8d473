// The routing envelope (route/envelope.h): its bytes as the README lays
// them out, the round trip, and refusals of outside bytes.
#include "route/envelope.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace acomms::route {
namespace {

Envelope sample() {
  Envelope e;
  e.origin = 0x0102;
  e.destination = 0x0304;
  e.seq = 0xbeef;
  e.hops = 2;
  e.hop_limit = 8;
  e.ttl_s = 1800;
  e.value_tenths = 15;
  e.payload = std::string("\x20\x01\x02\x03", 4);  // some DCCL message, never decoded here
  return e;
}

TEST(RouteEnvelopeTest, BytesFollowTheDocumentedLayout) {
  std::string bytes = encode_envelope(sample(), kDefaultEnvelopeId);
  const std::string expected(
      "\xff\xff"   // DCCL id header of 32767: ((32767 << 1) | 1) little-endian
      "\x82"       // hops 2, limit 8
      "\x02\x01"   // origin 0x0102
      "\x04\x03"   // destination 0x0304
      "\xef\xbe"   // seq 0xbeef
      "\x08\x07"   // ttl 1800 s
      "\x0f"       // value_base 1.5
      "\x04"       // 4 message bytes
      "\x20\x01\x02\x03",
      17);
  EXPECT_EQ(bytes, expected);
  EXPECT_EQ(bytes.size(), kEnvelopeOverheadBytes + 4);
}

TEST(RouteEnvelopeTest, DecodesWhatItEncodesAndSaysHowManyBytesItUsed) {
  Envelope e = sample();
  std::string frame = encode_envelope(e, 200) + "trailing message";
  size_t used = 0;
  std::string error;
  auto decoded = decode_envelope(frame, 200, &used, &error);
  ASSERT_TRUE(decoded) << error;
  EXPECT_EQ(*decoded, e);
  EXPECT_EQ(used, kEnvelopeOverheadBytes + e.payload.size());
  EXPECT_EQ(decoded->identity(), (MessageIdentity{0x0102, 0xbeef}));
}

TEST(RouteEnvelopeTest, OtherDcclIdsAreNotEnvelopes) {
  std::string bytes = encode_envelope(sample(), 200);
  EXPECT_TRUE(starts_envelope(bytes, 200));
  EXPECT_FALSE(starts_envelope(bytes, 201));
  EXPECT_FALSE(starts_envelope(std::string("\x20\x01", 2), 200));  // a one-byte id (16)
  std::string error;
  EXPECT_FALSE(decode_envelope(bytes, 201, nullptr, &error));
  EXPECT_NE(error.find("not an envelope"), std::string::npos);
}

TEST(RouteEnvelopeTest, EveryTruncationIsRefusedWithAReason) {
  std::string bytes = encode_envelope(sample(), kDefaultEnvelopeId);
  for (size_t n = 0; n < bytes.size(); ++n) {
    std::string error;
    EXPECT_FALSE(decode_envelope(bytes.substr(0, n), kDefaultEnvelopeId, nullptr, &error)) << n;
    EXPECT_FALSE(error.empty()) << n;
  }
}

TEST(RouteEnvelopeTest, FieldsOutOfRangeAreRefusedOnTheWayIn) {
  std::string good = encode_envelope(sample(), kDefaultEnvelopeId);
  std::string error;
  std::string limit_zero = good;
  limit_zero[2] = '\x02';  // hops 2, limit 0
  EXPECT_FALSE(decode_envelope(limit_zero, kDefaultEnvelopeId, nullptr, &error));
  std::string past_limit = good;
  past_limit[2] = '\x2f';  // hops 15, limit 2
  EXPECT_FALSE(decode_envelope(past_limit, kDefaultEnvelopeId, nullptr, &error));
  std::string broadcast = good;
  broadcast[5] = broadcast[6] = '\0';
  EXPECT_FALSE(decode_envelope(broadcast, kDefaultEnvelopeId, nullptr, &error));
  std::string empty = good.substr(0, kEnvelopeOverheadBytes);
  empty[12] = '\0';
  EXPECT_FALSE(decode_envelope(empty, kDefaultEnvelopeId, nullptr, &error));
}

TEST(RouteEnvelopeTest, EncodeRefusesWhatTheLayoutCannotHold) {
  Envelope e = sample();
  EXPECT_THROW(encode_envelope(e, 127), std::invalid_argument);  // a one-byte id is the users'
  EXPECT_THROW(encode_envelope(e, 32768), std::invalid_argument);
  e.payload.assign(256, 'x');
  EXPECT_THROW(encode_envelope(e, kDefaultEnvelopeId), std::invalid_argument);
  e = sample();
  e.payload.clear();
  EXPECT_THROW(encode_envelope(e, kDefaultEnvelopeId), std::invalid_argument);
  e = sample();
  e.hops = 9;
  EXPECT_THROW(encode_envelope(e, kDefaultEnvelopeId), std::invalid_argument);
  e = sample();
  e.hop_limit = 16;
  EXPECT_THROW(encode_envelope(e, kDefaultEnvelopeId), std::invalid_argument);
  e = sample();
  e.destination = 0;
  EXPECT_THROW(encode_envelope(e, kDefaultEnvelopeId), std::invalid_argument);
}

TEST(RouteEnvelopeTest, PriorityAndTtlSaturateInsteadOfWrapping) {
  EXPECT_EQ(value_to_tenths(1.0), 10);
  EXPECT_EQ(value_to_tenths(2.54), 25);
  EXPECT_EQ(value_to_tenths(1e9), 255);
  EXPECT_EQ(value_to_tenths(-3), 0);
  EXPECT_EQ(ttl_to_seconds(1799.9), 1799);
  EXPECT_EQ(ttl_to_seconds(1e12), 65535);
  EXPECT_EQ(ttl_to_seconds(-1), 0);
  EXPECT_EQ(ttl_to_seconds(std::nan("")), 0);
}

}  // namespace
}  // namespace acomms::route
