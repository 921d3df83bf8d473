// The consistency announce's bytes (node/consistency_announce.h): six bytes,
// a DCCL id header then the digest; decoding received bytes refuses, saying
// why, whatever is not one, and never reads past its input.

#include "node/consistency_announce.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace acomms::node {
namespace {

TEST(ConsistencyAnnounce, IsSixBytesTheIdHeaderThenTheDigestMostSignificantFirst) {
  const std::string bytes = encode_announce(0x1a2b3c4d, kDefaultAnnounceId);
  ASSERT_EQ(bytes.size(), kAnnounceBytes);
  EXPECT_EQ(bytes.size(), 6u);
  // (32766 << 1) | 1 = 0xfffd, little-endian: a two-byte DCCL id header.
  EXPECT_EQ(bytes, std::string("\xfd\xff\x1a\x2b\x3c\x4d", 6));
}

TEST(ConsistencyAnnounce, DecodesWhatItEncodesAndIgnoresWhatFollows) {
  for (uint32_t id : {128u, 200u, kDefaultAnnounceId, 32767u}) {
    for (uint32_t digest : {0u, 1u, 0x80000000u, 0xffffffffu, 0x1a2b3c4du}) {
      std::string error;
      EXPECT_EQ(decode_announce(encode_announce(digest, id) + "more", id, &error), std::optional<uint32_t>(digest))
          << error;
    }
  }
}

TEST(ConsistencyAnnounce, RefusesTruncatedBytesSayingSo) {
  const std::string bytes = encode_announce(0x1a2b3c4d, kDefaultAnnounceId);
  for (size_t n = 0; n < bytes.size(); ++n) {
    std::string error;
    EXPECT_EQ(decode_announce(bytes.substr(0, n), kDefaultAnnounceId, &error), std::nullopt) << n;
    EXPECT_FALSE(error.empty()) << n;
    if (n >= 2) {
      EXPECT_NE(error.find("truncated"), std::string::npos) << error;
    }
  }
}

TEST(ConsistencyAnnounce, RefusesAnotherIdAndAnIdOutOfRange) {
  std::string error;
  EXPECT_EQ(decode_announce(encode_announce(7, 200), kDefaultAnnounceId, &error), std::nullopt);
  EXPECT_NE(error.find("DCCL id differs"), std::string::npos) << error;
  // A one-byte DCCL id header (a user type's id 20) is not an announce.
  EXPECT_EQ(decode_announce(std::string("\x28\x00\x00\x00\x00\x00", 6), kDefaultAnnounceId, &error), std::nullopt);
  EXPECT_EQ(decode_announce(encode_announce(7, 200), 127, &error), std::nullopt);
  EXPECT_NE(error.find("out of range"), std::string::npos) << error;
  EXPECT_FALSE(starts_announce(encode_announce(7, 200), 40000));
}

TEST(ConsistencyAnnounce, EncodeRefusesAnIdOutsideTwoByteDcclIds) {
  EXPECT_THROW(encode_announce(1, 127), std::invalid_argument);
  EXPECT_THROW(encode_announce(1, 32768), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::node
