// Fixed decentralized TDMA: slot times exactly on cycle multiples since
// midnight UTC (or the epoch), own slots only, cycle changes at a boundary.

#include "mac/fixed_mac.h"

#include <gtest/gtest.h>

#include "mac/cycle_grid.h"
#include "mac_test_util.h"
#include "util/seconds.h"

namespace acomms::mac {
namespace {

using namespace testing;

TEST(CycleGrid, MultiplesOfTheCycleSinceMidnight) {
  CycleGrid grid(std::nullopt, std::chrono::seconds(30));
  EXPECT_EQ(grid.next(day_ms(1000500)).start, day_s(1020));
  EXPECT_EQ(grid.next(day_ms(1000500)).count, 34);
  EXPECT_EQ(grid.next(day_s(1020)).start, day_s(1020));  // "at or after"
  EXPECT_EQ(grid.containing(day_ms(1000500))->start, day_s(990));
  EXPECT_EQ(grid.containing(day_ms(1000500))->count, 33);
  // The day before: its own midnight.
  EXPECT_EQ(grid.next(day_s(-15)).start, day_s(0));
  EXPECT_EQ(grid.next(day_s(-15)).count, 0);
}

TEST(CycleGrid, RealignsAtMidnightWhenTheDayIsNotAWholeNumberOfCycles) {
  // 86400 / 70 = 1234 cycles and 20 s: cycle 1233 ends at 86380, and the
  // next cycle is cycle 0 at midnight, not 86380.
  CycleGrid grid(std::nullopt, std::chrono::seconds(70));
  EXPECT_EQ(grid.next(day_s(86300)).start, day_s(86310));
  EXPECT_EQ(grid.next(day_s(86300)).count, 1233);
  EXPECT_EQ(grid.next(day_s(86311)).start, day_s(86400));
  EXPECT_EQ(grid.next(day_s(86311)).count, 0);
  EXPECT_FALSE(grid.containing(day_s(86390)).has_value());  // the silent remainder
}

TEST(CycleGrid, EpochNeverRealigns) {
  const double epoch = static_cast<double>(kDay) + 7.25;
  CycleGrid grid(epoch, std::chrono::seconds(30));
  EXPECT_EQ(grid.next(day_s(8)).start, day_ms(37250));
  EXPECT_EQ(grid.next(day_s(8)).count, 1);
  EXPECT_EQ(grid.containing(day_s(0))->start, day_ms(-22750));  // before the epoch
  EXPECT_EQ(grid.containing(day_s(0))->count, -1);
  EXPECT_EQ(grid.next(day_s(86400)).start, day_ms(86407250));
}

Cycle three_nodes() { return {slot(1, 10), slot(2, 10), slot(3, 10)}; }

TEST(FixedMac, OwnSlotsExactlyOnCycleMultiplesSinceMidnight) {
  core::SimulatedScheduler scheduler(day_ms(1000500));
  FakeDriver driver(scheduler);
  FixedMac mac(three_nodes(), 2, std::nullopt, scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(1200));
  // Node 2's slot starts 10 s into each 30 s cycle. At 1000.5 that of the
  // cycle at 990 (1000) has passed, so the first is 1030.
  std::vector<core::Clock::time_point> expected;
  for (int64_t t = 1030; t <= 1200; t += 30) expected.push_back(day_s(t));
  EXPECT_EQ(driver.times(), expected);
  for (const Sent& sent : driver.sent) {
    EXPECT_EQ(sent.transmission.src(), 2);
    EXPECT_EQ(sent.transmission.dest(), -1);
    EXPECT_EQ(sent.transmission.slot_seconds(), 10);
    EXPECT_EQ(sent.transmission.type(), v1::ModemTransmission::DATA);
    EXPECT_DOUBLE_EQ(sent.transmission.time(), util::seconds_since_epoch(sent.when));
  }
}

TEST(FixedMac, JoinsMidCycleAtTheNextOwnSlot) {
  core::SimulatedScheduler scheduler(day_s(995));
  FakeDriver driver(scheduler);
  FixedMac mac(three_nodes(), 2, std::nullopt, scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(1001));
  EXPECT_EQ(driver.times(), std::vector<core::Clock::time_point>{day_s(1000)});
}

TEST(FixedMac, NoOwnSlotNoTransmission) {
  core::SimulatedScheduler scheduler(day_s(0));
  FakeDriver driver(scheduler);
  FixedMac mac(three_nodes(), 9, std::nullopt, scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(600));
  EXPECT_TRUE(driver.sent.empty());
}

TEST(FixedMac, AlignsToTheEpoch) {
  core::SimulatedScheduler scheduler(day_s(0));
  FakeDriver driver(scheduler);
  FixedMac mac(three_nodes(), 3, static_cast<double>(kDay) + 7.25, scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(100));
  // Epoch + 30 k + 20: the cycle at -22.75 s has its slot 3 at -2.75 s.
  EXPECT_EQ(driver.times(),
            (std::vector<core::Clock::time_point>{day_ms(27250), day_ms(57250), day_ms(87250)}));
}

TEST(FixedMac, MidnightRemainderIsSilentAndCycleZeroStartsAtMidnight) {
  core::SimulatedScheduler scheduler(day_s(86300));
  FakeDriver driver(scheduler);
  FixedMac mac({slot(4, 35), slot(5, 35)}, 4, std::nullopt, scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(86400 + 71));
  EXPECT_EQ(driver.times(), (std::vector<core::Clock::time_point>{
                                day_s(86310), day_s(86400), day_s(86470)}));
}

TEST(FixedMac, CycleChangeTakesEffectAtTheNextBoundary) {
  core::SimulatedScheduler scheduler(day_s(0));
  FakeDriver driver(scheduler);
  FixedMac mac({slot(1, 10), slot(2, 10)}, 1, std::nullopt, scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(25));
  mac.set_cycle({slot(2, 5), slot(1, 5), slot(3, 5)});
  EXPECT_EQ(mac.cycle().size(), 2u);  // not yet
  scheduler.run_until(day_s(39));
  EXPECT_EQ(mac.cycle().size(), 2u);
  scheduler.run_until(day_s(81));
  EXPECT_EQ(mac.cycle().size(), 3u);
  // Old cycle at 0 and 20; its boundary at 40 switches to the 15 s cycle,
  // whose next boundary is 45: node 1 then sends 5 s into each.
  EXPECT_EQ(driver.times(), (std::vector<core::Clock::time_point>{
                                day_s(0), day_s(20), day_s(50), day_s(65), day_s(80)}));
  for (const Sent& sent : driver.sent) EXPECT_EQ(sent.transmission.src(), 1);
  EXPECT_EQ(driver.sent.back().transmission.slot_seconds(), 5);
}

TEST(FixedMac, SameLengthChangeKeepsTheBeat) {
  core::SimulatedScheduler scheduler(day_s(0));
  FakeDriver driver(scheduler);
  FixedMac mac({slot(1, 10), slot(2, 10)}, 1, std::nullopt, scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(5));
  mac.set_cycle({slot(2, 10), slot(1, 10)});
  scheduler.run_until(day_s(61));
  EXPECT_EQ(driver.times(), (std::vector<core::Clock::time_point>{
                                day_s(0), day_s(30), day_s(50)}));
}

TEST(FixedMac, StopStops) {
  core::SimulatedScheduler scheduler(day_s(0));
  FakeDriver driver(scheduler);
  FixedMac mac({slot(1, 10)}, 1, std::nullopt, scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(25));
  mac.stop();
  scheduler.run_until(day_s(100));
  EXPECT_EQ(driver.sent.size(), 3u);
  EXPECT_EQ(scheduler.pending(), 0u);
}

TEST(FixedMac, FractionalSlotsStayExact) {
  // 0.1 s slots: a day of them must not drift by a nanosecond.
  core::SimulatedScheduler scheduler(day_s(86399));
  FakeDriver driver(scheduler);
  FixedMac mac({slot(1, 0.1), slot(2, 0.2)}, 2, std::nullopt, scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_ms(86400100));
  EXPECT_EQ(driver.times(), (std::vector<core::Clock::time_point>{
                                day_ms(86399200), day_ms(86399500), day_ms(86399800),
                                day_ms(86400100)}));
}

}  // namespace
}  // namespace acomms::mac
