// Little-endian fields: exact bytes, least significant first; round trips at
// every width; a short input is refused and left untouched.

#include "util/little_endian.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <string_view>

namespace acomms::util {
namespace {

TEST(LittleEndian, PutWritesLeastSignificantByteFirst) {
  std::string out;
  put_le(&out, 0x0102030405060708ULL, 8);
  EXPECT_EQ(out, std::string("\x08\x07\x06\x05\x04\x03\x02\x01", 8));
}

TEST(LittleEndian, PutKeepsOnlyTheLowBytesOfItsWidth) {
  std::string out;
  put_le(&out, 0xAABBCCDDULL, 2);
  put_le(&out, 0x1FFULL, 1);
  EXPECT_EQ(out, std::string("\xDD\xCC\xFF", 3));
}

TEST(LittleEndian, PutAppendsToWhatIsThere) {
  std::string out = "x";
  put_le(&out, 1, 4);
  EXPECT_EQ(out, std::string("x\x01\x00\x00\x00", 5));
}

TEST(LittleEndian, LoadReadsHighBytesWithoutSignExtension) {
  const unsigned char bytes[] = {0xFF, 0x80, 0x00, 0x7F};
  EXPECT_EQ(load_le(bytes, 4), 0x7F0080FFULL);
  EXPECT_EQ(load_le(bytes, 2), 0x80FFULL);
}

TEST(LittleEndian, EveryWidthRoundTrips) {
  for (int width = 1; width <= 8; ++width) {
    const uint64_t value = 0xF1E2D3C4B5A69788ULL >> (8 * (8 - width));
    std::string out;
    put_le(&out, value, width);
    ASSERT_EQ(out.size(), static_cast<size_t>(width));
    std::string_view in = out;
    uint64_t back = 0;
    ASSERT_TRUE(take_le(&in, width, &back));
    EXPECT_EQ(back, value) << "width " << width;
    EXPECT_TRUE(in.empty());
  }
}

TEST(LittleEndian, TakeConsumesOnlyItsWidth) {
  std::string_view in("\x01\x02\x03", 3);
  uint64_t value = 0;
  ASSERT_TRUE(take_le(&in, 2, &value));
  EXPECT_EQ(value, 0x0201u);
  EXPECT_EQ(in, std::string_view("\x03", 1));
}

TEST(LittleEndian, TakeRefusesAShortInputAndLeavesItUntouched) {
  std::string_view in("\x01\x02\x03", 3);
  uint64_t value = 42;
  EXPECT_FALSE(take_le(&in, 4, &value));
  EXPECT_EQ(in.size(), 3u);
  EXPECT_EQ(value, 42u);
}

}  // namespace
}  // namespace acomms::util
