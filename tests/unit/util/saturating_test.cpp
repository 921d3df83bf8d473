// Saturating arithmetic stops at the maximum, exactly at the limit and
// beyond it, and is plain arithmetic below it.

#include "util/saturating.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace acomms::util {
namespace {

constexpr uint64_t kMax = std::numeric_limits<uint64_t>::max();

TEST(SaturatingAdd, BelowTheLimitIsPlainAddition) {
  EXPECT_EQ(saturating_add(0, 0), 0u);
  EXPECT_EQ(saturating_add(2, 3), 5u);
  EXPECT_EQ(saturating_add(kMax - 1, 0), kMax - 1);
}

TEST(SaturatingAdd, ReachingTheMaximumExactlyIsNotOverflow) {
  EXPECT_EQ(saturating_add(kMax - 1, 1), kMax);
  EXPECT_EQ(saturating_add(1, kMax - 1), kMax);
  EXPECT_EQ(saturating_add(kMax, 0), kMax);
  EXPECT_EQ(saturating_add(0, kMax), kMax);
}

TEST(SaturatingAdd, PastTheMaximumStaysAtTheMaximum) {
  EXPECT_EQ(saturating_add(kMax, 1), kMax);
  EXPECT_EQ(saturating_add(1, kMax), kMax);
  EXPECT_EQ(saturating_add(kMax, kMax), kMax);
  EXPECT_EQ(saturating_add(kMax / 2 + 1, kMax / 2 + 1), kMax);
}

TEST(SaturatingMul, BelowTheLimitIsPlainMultiplication) {
  EXPECT_EQ(saturating_mul(0, kMax), 0u);
  EXPECT_EQ(saturating_mul(kMax, 0), 0u);
  EXPECT_EQ(saturating_mul(6, 7), 42u);
  EXPECT_EQ(saturating_mul(kMax, 1), kMax);
  EXPECT_EQ(saturating_mul(uint64_t{1} << 32, (uint64_t{1} << 32) - 1),
            kMax - ((uint64_t{1} << 32) - 1));
}

TEST(SaturatingMul, PastTheMaximumStaysAtTheMaximum) {
  EXPECT_EQ(saturating_mul(uint64_t{1} << 32, uint64_t{1} << 32), kMax);
  EXPECT_EQ(saturating_mul(kMax, 2), kMax);
  EXPECT_EQ(saturating_mul(kMax, kMax), kMax);
}

}  // namespace
}  // namespace acomms::util
