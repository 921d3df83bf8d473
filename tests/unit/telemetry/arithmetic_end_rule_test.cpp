// The arithmetic coder's end (Schneider 2013 eq. 3.30-3.32, spec section 4):
// one test per row of the table, each checking the exact bits written and
// that the decoder stops on the last of them whatever follows.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dccl/arithmetic_coder.h"

namespace acomms::dccl::arith {
namespace {

// Codes symbols, returns the coder's bits as "0"/"1" in stream order, and
// checks that a decoder reading them followed by 1s and by 0s gets the
// symbols back and stops right after them.
std::string code(const std::vector<uint32_t>& frequencies, const std::vector<size_t>& symbols) {
  const FrequencyTable table(frequencies);
  std::string bytes;
  BitWriter out(&bytes);
  Encoder encoder(out);
  for (size_t s : symbols) encoder.encode(table, s);
  encoder.finish();
  const uint64_t length = out.position();
  std::string bits;
  {
    BitReader in(bytes);
    for (uint64_t i = 0; i < length; ++i) bits += in.read(1) ? '1' : '0';
  }
  for (unsigned filler : {0u, 1u}) {
    std::string stream;
    BitWriter w(&stream);
    for (char c : bits) w.write(c == '1', 1);
    for (int i = 0; i < 40; ++i) w.write(filler, 1);
    BitReader in(stream);
    Decoder decoder(in);
    for (size_t s : symbols) EXPECT_EQ(decoder.decode(table), s);
    EXPECT_EQ(in.position(), length) << "filler " << filler;
  }
  return bits;
}

TEST(ArithmeticEndRule, WholeIntervalWithoutFollowBitsEndsWithNothing) {
  // [0, 1): a certain symbol costs nothing at all.
  EXPECT_EQ(code({5}, {0, 0, 0}), "");
  // [0, 1/2) renormalises to [0, 1) after writing 0: no end bits.
  EXPECT_EQ(code({1, 1}, {0}), "0");
}

TEST(ArithmeticEndRule, WholeIntervalWithFollowBitsEndsWithOneBitThenTheFollowBits) {
  // [1/4, 3/4) straddles the middle: one follow bit pending, interval [0, 1).
  EXPECT_EQ(code({1, 2, 1}, {1}), "01");
  // Two middle expansions: [3/8, 5/8) -> two follow bits.
  EXPECT_EQ(code({3, 2, 3}, {1}), "011");
}

TEST(ArithmeticEndRule, HighAtOneLowBelowHalfEndsWithOne) {
  // [1/3, 1)
  EXPECT_EQ(code({1, 2}, {1}), "1");
}

TEST(ArithmeticEndRule, LowAtZeroHighAboveHalfEndsWithZero) {
  // [0, 2/3)
  EXPECT_EQ(code({2, 1}, {0}), "0");
}

TEST(ArithmeticEndRule, LowBelowQuarterHighAtLeastHalfEndsWithZeroOne) {
  // [0.1, 0.9)
  EXPECT_EQ(code({1, 8, 1}, {1}), "01");
}

TEST(ArithmeticEndRule, LowBelowHalfHighAtLeastThreeQuartersEndsWithOneZero) {
  // [0.3, 0.9)
  EXPECT_EQ(code({3, 6, 1}, {1}), "10");
}

TEST(ArithmeticEndRule, PendingFollowBitsComeOutOppositeToTheNextBit) {
  // [1/4, 3/4) pends a bit; [0, 1/4) then writes 0 (releasing the pending 1)
  // and 0 again; [3/4, 1) writes 1, releasing a 0, and 1 again.
  EXPECT_EQ(code({1, 2, 1}, {1, 0}), "010");
  EXPECT_EQ(code({1, 2, 1}, {1, 2}), "101");
}

TEST(ArithmeticEndRule, ThreeUniformAxesCostTwentyOrTwentyOneBits) {
  // log2(101^3) = 19.97: whole bits, so 20 or 21 (never less).
  const std::vector<uint32_t> uniform(101, 1);
  for (size_t a : {0u, 50u, 100u, 7u}) {
    for (size_t b : {0u, 50u, 100u, 33u}) {
      const size_t bits = code(uniform, {a, b, 100 - a}).size();
      EXPECT_GE(bits, 20u);
      EXPECT_LE(bits, 21u);
    }
  }
}

}  // namespace
}  // namespace acomms::dccl::arith
