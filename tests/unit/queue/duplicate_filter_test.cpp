// DuplicateFilter (daemon/queue/duplicate_filter.h) on its own: the same
// source and bytes within the window is a retransmission; anything else,
// or after the window, is not; memory is bounded; window 0 turns it off.

#include "queue/duplicate_filter.h"

#include <gtest/gtest.h>

#include <string>

namespace acomms::queue {
namespace {

constexpr double kT = 1'700'000'000;

TEST(DuplicateFilterTest, SameSourceAndBytesWithinTheWindowIsADuplicate) {
  DuplicateFilter filter(60);
  EXPECT_FALSE(filter.seen(4, "\x01\x02\x03", kT));
  EXPECT_TRUE(filter.seen(4, "\x01\x02\x03", kT + 1));
  EXPECT_TRUE(filter.seen(4, "\x01\x02\x03", kT + 59));
}

TEST(DuplicateFilterTest, OtherSourceOrOtherBytesIsNot) {
  DuplicateFilter filter(60);
  EXPECT_FALSE(filter.seen(4, "abc", kT));
  EXPECT_FALSE(filter.seen(5, "abc", kT + 1)) << "another source";
  EXPECT_FALSE(filter.seen(4, "abd", kT + 1)) << "other bytes";
  EXPECT_FALSE(filter.seen(4, "ab", kT + 1)) << "a prefix";
  EXPECT_FALSE(filter.seen(4, "abcd", kT + 1)) << "an extension";
  EXPECT_FALSE(filter.seen(4, std::string("abc\0", 4), kT + 1)) << "a trailing NUL";
  EXPECT_FALSE(filter.seen(-1, "abc", kT + 1)) << "unknown source";
  // Each of those is now remembered in its own right.
  EXPECT_TRUE(filter.seen(5, "abc", kT + 2));
  EXPECT_TRUE(filter.seen(4, "abd", kT + 2));
  EXPECT_TRUE(filter.seen(-1, "abc", kT + 2));
}

TEST(DuplicateFilterTest, BytesWithNulsAreComparedWhole) {
  DuplicateFilter filter(60);
  std::string a("\x00\x00\x01", 3);
  std::string b("\x00\x00\x02", 3);
  EXPECT_FALSE(filter.seen(1, a, kT));
  EXPECT_FALSE(filter.seen(1, b, kT));
  EXPECT_TRUE(filter.seen(1, a, kT));
}

TEST(DuplicateFilterTest, AfterTheWindowItIsNotADuplicate) {
  DuplicateFilter filter(10);
  EXPECT_FALSE(filter.seen(4, "abc", kT));
  EXPECT_TRUE(filter.seen(4, "abc", kT + 9.5));
  EXPECT_FALSE(filter.seen(4, "abc", kT + 10.5)) << "window passed since the first";
  // That arrival starts a new window.
  EXPECT_TRUE(filter.seen(4, "abc", kT + 15));
  EXPECT_FALSE(filter.seen(4, "abc", kT + 21));
}

TEST(DuplicateFilterTest, CapacityForgetsTheOldestFirst) {
  DuplicateFilter filter(1000, 3);
  EXPECT_FALSE(filter.seen(1, "a", kT));
  EXPECT_FALSE(filter.seen(1, "b", kT + 1));
  EXPECT_FALSE(filter.seen(1, "c", kT + 2));
  EXPECT_FALSE(filter.seen(1, "d", kT + 3));  // forgets "a"
  EXPECT_TRUE(filter.seen(1, "b", kT + 4));
  EXPECT_TRUE(filter.seen(1, "c", kT + 4));
  EXPECT_TRUE(filter.seen(1, "d", kT + 4));
  EXPECT_FALSE(filter.seen(1, "a", kT + 4)) << "the oldest was not the one forgotten";
  // "a" is back, so "b" (now the oldest) went.
  EXPECT_FALSE(filter.seen(1, "b", kT + 5));
}

TEST(DuplicateFilterTest, ManyDistinctMessagesStayWithinCapacity) {
  DuplicateFilter filter(1e9, 100);
  for (int i = 0; i < 10000; ++i) EXPECT_FALSE(filter.seen(1, std::to_string(i), kT + i * 1e-3));
  for (int i = 9900; i < 10000; ++i) EXPECT_TRUE(filter.seen(1, std::to_string(i), kT + 20));
  EXPECT_FALSE(filter.seen(1, "0", kT + 20));
}

TEST(DuplicateFilterTest, ForgettingForWantOfRoomInsideTheWindowIsCounted) {
  DuplicateFilter filter(10, 2);
  EXPECT_FALSE(filter.seen(1, "a", kT));
  EXPECT_FALSE(filter.seen(1, "b", kT + 1));
  EXPECT_FALSE(filter.seen(1, "c", kT + 2));  // "a" still inside its window
  EXPECT_EQ(filter.forgotten_early(), 1u);
  EXPECT_FALSE(filter.seen(1, "d", kT + 12.5));  // "b" and "c" expired first: room
  EXPECT_FALSE(filter.seen(1, "e", kT + 12.6));
  EXPECT_EQ(filter.forgotten_early(), 1u) << "an expired entry counted as forgotten early";
}

// README: "over eight messages a second for the default 1800 s ttl" (a
// stamped type remembers for 1800 + 2 x 60 s).
TEST(DuplicateFilterTest, DefaultCapacityHoldsEightMessagesASecondForTheDefaultTtl) {
  DuplicateFilter filter(1800 + 2 * 60);
  EXPECT_GE(filter.capacity(), 8u * (1800 + 2 * 60));
}

TEST(DuplicateFilterTest, WindowZeroTurnsItOff) {
  DuplicateFilter filter(0);
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(filter.seen(4, "abc", kT));
}

// What a restarted node fills in from its event log counts as seen, until
// the window has passed since it was received (not since it was remembered).
TEST(DuplicateFilterTest, RememberedMessagesAreDuplicatesUntilTheirWindowEnds) {
  DuplicateFilter filter(60);
  filter.remember(4, std::string("a\0b", 3), kT);
  filter.remember(4, "later", kT + 30);
  EXPECT_TRUE(filter.seen(4, std::string("a\0b", 3), kT + 50));
  EXPECT_FALSE(filter.seen(5, std::string("a\0b", 3), kT + 50)) << "another source's bytes";
  EXPECT_FALSE(filter.seen(4, std::string("a\0b", 3), kT + 61)) << "its window ended at kT + 60";
  EXPECT_TRUE(filter.seen(4, "later", kT + 61));
}

TEST(DuplicateFilterTest, RememberIsBoundedByCapacityAndOffWithWindowZero) {
  DuplicateFilter filter(1000, 2);
  filter.remember(1, "x", kT);
  filter.remember(1, "y", kT + 1);
  filter.remember(1, "z", kT + 2);
  EXPECT_FALSE(filter.seen(1, "x", kT + 3)) << "the oldest was forgotten";
  DuplicateFilter off(0);
  off.remember(1, "x", kT);
  EXPECT_FALSE(off.seen(1, "x", kT));
}

}  // namespace
}  // namespace acomms::queue
