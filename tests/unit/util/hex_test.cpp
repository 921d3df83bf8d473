// Hex: exact digits in each case, round trips, and the two ways a string
// fails to decode (odd length first, else the first bad character's place).

#include "util/hex.h"

#include <gtest/gtest.h>

#include <string>

namespace acomms::util {
namespace {

const std::string kBytes("\x00\x01\x7f\x80\xab\xff", 6);

TEST(Hex, EncodesTwoDigitsPerByteHighNibbleFirst) {
  EXPECT_EQ(hex_encode(kBytes), "00017f80abff");
  EXPECT_EQ(hex_encode(kBytes, HexCase::kUpper), "00017F80ABFF");
  EXPECT_EQ(hex_encode(""), "");
}

TEST(Hex, DecodesEitherCase) {
  HexError error;
  EXPECT_EQ(hex_decode("00017f80abff", &error), kBytes);
  EXPECT_EQ(hex_decode("00017F80ABFF", &error), kBytes);
  EXPECT_EQ(hex_decode("aBfF", &error), std::string("\xab\xff", 2));
  EXPECT_EQ(hex_decode("", &error), std::string());
}

TEST(Hex, EveryByteRoundTrips) {
  std::string all;
  for (int b = 0; b < 256; ++b) all += static_cast<char>(b);
  HexError error;
  EXPECT_EQ(hex_decode(hex_encode(all), &error), all);
  EXPECT_EQ(hex_decode(hex_encode(all, HexCase::kUpper), &error), all);
}

TEST(Hex, OddLengthIsReportedBeforeAnyBadCharacter) {
  HexError error;
  EXPECT_FALSE(hex_decode("zz0", &error).has_value());
  EXPECT_TRUE(error.odd_length);
}

TEST(Hex, ABadCharacterIsReportedByItsOneBasedPosition) {
  HexError error;
  EXPECT_FALSE(hex_decode("0g", &error).has_value());
  EXPECT_FALSE(error.odd_length);
  EXPECT_EQ(error.position, 2u);

  EXPECT_FALSE(hex_decode("00g0", &error).has_value());
  EXPECT_EQ(error.position, 3u);

  // Both digits of a pair bad: the first one is named.
  EXPECT_FALSE(hex_decode("12 x", &error).has_value());
  EXPECT_EQ(error.position, 3u);
}

TEST(Hex, DigitValues) {
  EXPECT_EQ(hex_digit_value('0'), 0);
  EXPECT_EQ(hex_digit_value('9'), 9);
  EXPECT_EQ(hex_digit_value('a'), 10);
  EXPECT_EQ(hex_digit_value('F'), 15);
  EXPECT_EQ(hex_digit_value('g'), -1);
  EXPECT_EQ(hex_digit_value('G'), -1);
  EXPECT_EQ(hex_digit_value('/'), -1);
  EXPECT_EQ(hex_digit_value(':'), -1);
  EXPECT_EQ(hex_digit_value('@'), -1);
  EXPECT_EQ(hex_digit_value('`'), -1);
}

}  // namespace
}  // namespace acomms::util
