// The gaps in a telemetry stream's sequence counted as packets sent and not
// received (telemetry/sequence_gaps.h): once, never for a late or replayed
// copy, not for a sender's fresh start or a jump too long to be losses,
// across the 12-bit wrap, per sender.
#include "telemetry/sequence_gaps.h"

#include <gtest/gtest.h>

namespace acomms::telemetry {
namespace {

TEST(SequenceGapsTest, TheFirstMessageIsTheBaselineAndTheNextInOrderMissesNothing) {
  SequenceGaps gaps;
  EXPECT_EQ(gaps.observe(2, 100, false), 0u);
  EXPECT_EQ(gaps.observe(2, 101, false), 0u);
  EXPECT_EQ(gaps.counters().missing, 0u);
}

TEST(SequenceGapsTest, AGapCountsEachMissingMessageOnceAndNotAgainWhenTheyComeLate) {
  SequenceGaps gaps;
  gaps.observe(2, 100, false);
  EXPECT_EQ(gaps.observe(2, 104, false), 3u) << "101, 102, 103";
  // The sender's resends of 101..103, and a replayed 104: nothing more.
  for (uint32_t late : {101u, 102u, 103u, 104u}) EXPECT_EQ(gaps.observe(2, late, false), 0u) << late;
  EXPECT_EQ(gaps.observe(2, 105, false), 0u);
  EXPECT_EQ(gaps.counters().missing, 3u);
  EXPECT_EQ(gaps.counters().late, 4u);
}

TEST(SequenceGapsTest, TheTwelveBitSequenceWrapsAndEachSenderIsItsOwn) {
  SequenceGaps gaps;
  gaps.observe(2, 4094, false);
  gaps.observe(3, 7, false);
  EXPECT_EQ(gaps.observe(2, 1, false), 2u) << "4095 and 0";
  EXPECT_EQ(gaps.observe(3, 8, false), 0u) << "sender 3's own count";
}

TEST(SequenceGapsTest, AFreshStartOrAJumpTooLongIsANewBaselineNotLosses) {
  SequenceGaps gaps;
  gaps.observe(2, 500, false);
  EXPECT_EQ(gaps.observe(2, 510, true), 0u) << "the sender restarted and counts anew";
  EXPECT_EQ(gaps.observe(2, 511, false), 0u) << "counted from the fresh start";
  EXPECT_EQ(gaps.observe(2, 511 + SequenceGaps::kMaxCounted + 2, false), 0u) << "silent for long: not losses";
  EXPECT_EQ(gaps.observe(2, 511 + SequenceGaps::kMaxCounted + 4, false), 1u) << "counted from the new baseline";
  EXPECT_EQ(gaps.counters().restarts, 1u);
  EXPECT_EQ(gaps.counters().jumps, 1u);
  // The longest gap still counted.
  SequenceGaps longest;
  longest.observe(2, 0, false);
  EXPECT_EQ(longest.observe(2, SequenceGaps::kMaxCounted + 1, false), static_cast<uint32_t>(SequenceGaps::kMaxCounted));
}

}  // namespace
}  // namespace acomms::telemetry
