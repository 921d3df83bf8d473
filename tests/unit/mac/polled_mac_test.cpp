// The polling master: every slot in order, back to back from start(), with
// the slot's src, dest, rate and length.

#include "mac/polled_mac.h"

#include <gtest/gtest.h>

#include "mac_test_util.h"
#include "util/seconds.h"

namespace acomms::mac {
namespace {

using namespace testing;

Cycle polls() { return {slot(1, 5, 2, 1), slot(3, 10, -1, 0), slot(2, 2.5, 0, 5)}; }

TEST(PolledMac, IssuesEverySlotInOrderBackToBack) {
  const core::Clock::time_point start = day_ms(123456);  // not aligned to anything
  core::SimulatedScheduler scheduler(start);
  FakeDriver driver(scheduler);
  PolledMac mac(polls(), scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(start + std::chrono::milliseconds(2 * 17500 + 5000));
  // Two whole cycles (17.5 s each) and the first slot of the third.
  const int64_t offsets_ms[] = {0, 5000, 15000, 17500, 22500, 32500, 35000, 40000};
  ASSERT_EQ(driver.sent.size(), std::size(offsets_ms));
  const Cycle cycle = polls();
  for (size_t i = 0; i < driver.sent.size(); ++i) {
    const Sent& sent = driver.sent[i];
    const Slot& expected = cycle[i % cycle.size()];
    EXPECT_EQ(sent.when, start + std::chrono::milliseconds(offsets_ms[i])) << i;
    EXPECT_EQ(sent.transmission.src(), expected.src) << i;
    EXPECT_EQ(sent.transmission.dest(), expected.dest) << i;
    EXPECT_EQ(sent.transmission.rate(), expected.rate) << i;
    EXPECT_EQ(sent.transmission.slot_seconds(), expected.seconds) << i;
    EXPECT_EQ(sent.transmission.type(), v1::ModemTransmission::DATA) << i;
    EXPECT_DOUBLE_EQ(sent.transmission.time(), util::seconds_since_epoch(sent.when));
  }
}

TEST(PolledMac, CycleChangeTakesEffectAtTheNextBoundary) {
  core::SimulatedScheduler scheduler(day_s(0));
  FakeDriver driver(scheduler);
  PolledMac mac(polls(), scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(6));  // slots 0 and 1 issued
  mac.set_cycle({slot(7, 4), slot(8, 4)});
  EXPECT_EQ(mac.cycle().size(), 3u);
  scheduler.run_until(day_ms(17500 + 8000));
  std::vector<int32_t> srcs;
  for (const Sent& sent : driver.sent) srcs.push_back(sent.transmission.src());
  // The cycle in progress finishes (slot src 2 at 15 s); the new one starts
  // at 17.5 s, then 21.5 s, 25.5 s.
  EXPECT_EQ(srcs, (std::vector<int32_t>{1, 3, 2, 7, 8, 7}));
  EXPECT_EQ(driver.sent.back().when, day_ms(25500));
  EXPECT_EQ(mac.cycle().size(), 2u);
}

TEST(PolledMac, StopStopsAndRestartBeginsAnew) {
  core::SimulatedScheduler scheduler(day_s(0));
  FakeDriver driver(scheduler);
  PolledMac mac(polls(), scheduler);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(6));
  mac.stop();
  EXPECT_EQ(scheduler.pending(), 0u);
  scheduler.run_until(day_s(100));
  EXPECT_EQ(driver.sent.size(), 2u);
  mac.start(driver.transmit());
  scheduler.run_until(day_s(100));
  ASSERT_EQ(driver.sent.size(), 3u);
  EXPECT_EQ(driver.sent.back().transmission.src(), 1);  // from slot 0
}

TEST(PolledMac, RejectsABadCycle) {
  core::SimulatedScheduler scheduler(day_s(0));
  EXPECT_THROW(PolledMac({}, scheduler), std::invalid_argument);
  EXPECT_THROW(PolledMac({slot(1, 0)}, scheduler), std::invalid_argument);
  PolledMac mac(polls(), scheduler);
  EXPECT_THROW(mac.set_cycle({slot(0, 5)}), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::mac
