// Time points as seconds since their clock's epoch: whole and fractional
// seconds, before the epoch, and the system clock's now as Unix time.

#include "util/seconds.h"

#include <gtest/gtest.h>

#include <chrono>

namespace acomms::util {
namespace {

using Nanos = std::chrono::time_point<std::chrono::system_clock, std::chrono::nanoseconds>;

TEST(Seconds, WholeAndFractionalSecondsSinceTheEpoch) {
  EXPECT_DOUBLE_EQ(seconds_since_epoch(Nanos(std::chrono::seconds(1'700'000'000))), 1.7e9);
  EXPECT_DOUBLE_EQ(seconds_since_epoch(Nanos(std::chrono::milliseconds(1500))), 1.5);
  EXPECT_DOUBLE_EQ(seconds_since_epoch(Nanos(std::chrono::nanoseconds(-250'000'000))), -0.25);
  EXPECT_DOUBLE_EQ(seconds_since_epoch(Nanos{}), 0.0);
}

TEST(Seconds, WorksForAnyClockAndPeriod) {
  using Steady = std::chrono::time_point<std::chrono::steady_clock, std::chrono::minutes>;
  EXPECT_DOUBLE_EQ(seconds_since_epoch(Steady(std::chrono::minutes(2))), 120.0);
}

TEST(Seconds, UnixNowIsTheSystemClockInSeconds) {
  const double before = seconds_since_epoch(std::chrono::system_clock::now());
  const double now = unix_seconds_now();
  const double after = seconds_since_epoch(std::chrono::system_clock::now());
  EXPECT_LE(before, now);
  EXPECT_LE(now, after);
  EXPECT_GT(now, 1.6e9);  // after September 2020: seconds, not milliseconds or minutes
  EXPECT_LT(now, 4.1e9);
}

}  // namespace
}  // namespace acomms::util
