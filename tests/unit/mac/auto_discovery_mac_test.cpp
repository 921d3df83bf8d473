// Auto-discovery on the simulated channel: nodes find each other, converge
// on one collision-free cycle, and forget silent nodes.

#include "mac/auto_discovery_mac.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>

#include "eval/simulated_channel.h"
#include "mac/blank_slot.h"
#include "mac_test_util.h"

namespace acomms::mac {
namespace {

using namespace testing;

std::vector<int32_t> srcs(const Cycle& cycle) {
  std::vector<int32_t> out;
  for (const Slot& s : cycle) out.push_back(s.src);
  return out;
}

TEST(BlankSlot, FigureRuleLastOrPenultimate) {
  int excited = 0;
  for (int64_t k = 0; k < 3000; ++k) {
    const size_t index = blank_slot_index(BlankRule::kFigure, 5, k, 42, 3);
    EXPECT_EQ(index, blank_excited(BlankRule::kFigure, k, 42, 3) ? 3u : 4u);
    EXPECT_EQ(blank_excited(BlankRule::kFigure, k, 42, 3), blank_hash(k, 42) % 3 == 0);
    excited += index == 3;
  }
  EXPECT_NEAR(excited, 1000, 100);  // one cycle in C
}

TEST(BlankSlot, HashIsPinned) {
  // Every node must compute the same H(k, S): never change these.
  // (Values from an independent big-integer evaluation of the formula.)
  EXPECT_EQ(blank_hash(0, 0), 0u);
  EXPECT_EQ(blank_hash(0, 3), 0x1e535eede31428f0ULL);
  EXPECT_EQ(blank_hash(1, 3), 0x1d0b14e4db018fedULL);
  EXPECT_EQ(blank_hash(-1, 100), 0x40feb766e895bd38ULL);
  EXPECT_EQ(blank_hash(1234, 350), 0x87288c2369d2e9bdULL);
}

TEST(BlankSlot, CongruenceRuleIsGobys) {
  for (int64_t k = -10; k < 30; ++k) {
    EXPECT_EQ(blank_slot_index(BlankRule::kCongruence, 3, k, 3, 3),
              ((k % 3 + 3) % 3 == 0) ? 1u : 2u) << k;
  }
}

TEST(BlankSlot, AnywhereRuleNeverLastWhenExcited) {
  std::vector<int> seen(6, 0);
  for (int64_t k = 0; k < 5000; ++k) {
    const size_t index = blank_slot_index(BlankRule::kAnywhere, 6, k, 99, 2);
    ASSERT_LT(index, 6u);
    if (!blank_excited(BlankRule::kAnywhere, k, 99, 2)) {
      EXPECT_EQ(index, 5u);
    }
    ++seen[index];
  }
  for (int count : seen) EXPECT_GT(count, 0);
  // Two slots: the only place before the last is the first, as in the figure.
  for (int64_t k = 0; k < 100; ++k)
    EXPECT_EQ(blank_slot_index(BlankRule::kAnywhere, 2, k, 5, 3),
              blank_slot_index(BlankRule::kFigure, 2, k, 5, 3));
}

// Nodes on one simulated channel (daemon/eval), for the hand-driven tests.
struct Network {
  explicit Network(core::Clock::time_point start, double p_collide = 1)
      : scheduler(start), channel(scheduler, std::chrono::milliseconds(13500), p_collide, 7) {}

  AutoDiscoveryMac& add(int32_t id, const AutoDiscoveryConfig& config) {
    macs.push_back(std::make_unique<AutoDiscoveryMac>(config, id, scheduler));
    AutoDiscoveryMac* mac = macs.back().get();
    channel.attach(id, [mac](const v1::ModemTransmission& t) { mac->on_receive(t); });
    return *mac;
  }
  void start(AutoDiscoveryMac& mac) {
    channel.switch_on(mac.own_id());
    const int32_t id = mac.own_id();
    mac.start([this, id](const v1::ModemTransmission& t) {
      sent.push_back(t);
      channel.transmit(id, t);
    });
  }

  core::SimulatedScheduler scheduler;
  eval::SimulatedChannel channel;
  std::vector<std::unique_ptr<AutoDiscoveryMac>> macs;
  std::vector<v1::ModemTransmission> sent;
};

AutoDiscoveryConfig fifteen_seconds(uint32_t coolness) {
  AutoDiscoveryConfig config;
  config.slot_seconds = 15;
  config.coolness = coolness;
  config.expire_cycles = 3;
  config.rate = 2;
  return config;
}

TEST(AutoDiscoveryMac, AloneItSendsOncePerTwoSlotCycleOnMidnightMultiples) {
  Network net(day_s(1000));
  AutoDiscoveryMac& mac = net.add(5, fifteen_seconds(3));
  net.start(mac);
  EXPECT_EQ(mac.activity(), AutoDiscoveryMac::Activity::kWaiting);
  net.scheduler.run_until(day_s(1020));
  ASSERT_EQ(net.sent.size(), 1u);
  EXPECT_DOUBLE_EQ(net.sent[0].time(), kDay + 1020.0);  // 1020 = 34 * 30
  EXPECT_EQ(net.sent[0].src(), 5);
  EXPECT_EQ(net.sent[0].dest(), -1);
  EXPECT_EQ(net.sent[0].rate(), 2);
  EXPECT_EQ(net.sent[0].slot_seconds(), 15);
  EXPECT_EQ(mac.cycle().size(), 2u);
  net.scheduler.run_until(day_s(1020 + 3000));
  for (const v1::ModemTransmission& t : net.sent) {
    const double since_midnight = t.time() - kDay;
    EXPECT_EQ(std::fmod(since_midnight, 15.0), 0.0);
    EXPECT_EQ(t.src(), 5);
  }
  EXPECT_EQ(net.sent.size(), 101u);  // once per 30 s cycle
}

TEST(AutoDiscoveryMac, TwoNodesDiscoverEachOtherAndShareOneCycle) {
  Network net(day_s(0));
  AutoDiscoveryMac& a = net.add(1, fifteen_seconds(3));
  AutoDiscoveryMac& b = net.add(2, fifteen_seconds(3));
  net.start(a);
  net.start(b);
  net.scheduler.run_until(day_s(10 * 45));
  EXPECT_EQ(a.known_ids(), (std::vector<int32_t>{1, 2}));
  EXPECT_EQ(b.known_ids(), (std::vector<int32_t>{1, 2}));
  ASSERT_TRUE(a.in_cycle());
  ASSERT_TRUE(b.in_cycle());
  EXPECT_EQ(a.cycle_start(), b.cycle_start());
  EXPECT_EQ(srcs(a.cycle()), srcs(b.cycle()));
  EXPECT_EQ(a.cycle().size(), 3u);
  // From then on, never together: each sends exactly once in every 45 s
  // cycle (the blank may move within a cycle; the nodes still agree).
  const size_t before = net.sent.size();
  net.scheduler.run_until(day_s(10 * 45 + 20 * 45));
  std::map<double, int> per_time;
  std::map<int64_t, std::vector<int32_t>> senders_per_cycle;
  for (size_t i = before; i < net.sent.size(); ++i) {
    ++per_time[net.sent[i].time()];
    senders_per_cycle[static_cast<int64_t>((net.sent[i].time() - kDay) / 45)].push_back(net.sent[i].src());
  }
  for (const auto& [time, count] : per_time) EXPECT_EQ(count, 1) << time - kDay;
  for (int64_t cycle = 10; cycle < 30; ++cycle) {
    std::vector<int32_t> senders = senders_per_cycle[cycle];
    std::sort(senders.begin(), senders.end());
    EXPECT_EQ(senders, (std::vector<int32_t>{1, 2})) << "cycle " << cycle;
  }
}

TEST(AutoDiscoveryMac, SilentNodeExpiresAfterExpireCycles) {
  Network net(day_s(0));
  AutoDiscoveryMac& a = net.add(1, fifteen_seconds(3));
  AutoDiscoveryMac& b = net.add(2, fifteen_seconds(3));
  net.start(a);
  net.start(b);
  net.scheduler.run_until(day_s(450));
  ASSERT_EQ(a.known_ids().size(), 2u);
  b.stop();  // node 2 falls silent
  // Its last transmission was heard at the latest 15 + 13.5 s into the last
  // 45 s cycle before 450; expire_cycles = 3: after 135 s of silence, at a
  // cycle boundary of node 1.
  core::Clock::time_point last_heard{};
  for (const v1::ModemTransmission& t : net.sent)
    if (t.src() == 2) last_heard = day_ms(static_cast<int64_t>(std::llround((t.time() - kDay) * 1000)) + 13500);
  std::optional<core::Clock::time_point> expired_at;
  for (core::Clock::time_point t = day_s(450); t < day_s(1200); t += std::chrono::seconds(15)) {
    net.scheduler.run_until(t + std::chrono::milliseconds(1));
    if (!expired_at && a.known_ids().size() == 1) expired_at = t;
  }
  ASSERT_TRUE(expired_at.has_value());
  EXPECT_GT(*expired_at - last_heard, std::chrono::seconds(135));
  EXPECT_LE(*expired_at - last_heard, std::chrono::seconds(135 + 45));
  // Back to a lone two-slot cycle.
  EXPECT_EQ(a.cycle().size(), 2u);
  EXPECT_EQ(a.known_ids(), std::vector<int32_t>{1});
}

TEST(AutoDiscoveryMac, RefusesSetCycleAndBadConfig) {
  core::SimulatedScheduler scheduler(day_s(0));
  AutoDiscoveryMac mac(fifteen_seconds(3), 1, scheduler);
  EXPECT_THROW(mac.set_cycle({slot(1, 10)}), std::invalid_argument);
  AutoDiscoveryConfig bad = fifteen_seconds(3);
  bad.coolness = 0;
  EXPECT_THROW(AutoDiscoveryMac(bad, 1, scheduler), std::invalid_argument);
  bad = fifteen_seconds(3);
  bad.slot_seconds = 0;
  EXPECT_THROW(AutoDiscoveryMac(bad, 1, scheduler), std::invalid_argument);
  bad = fifteen_seconds(3);
  bad.expire_cycles = 0;
  EXPECT_THROW(AutoDiscoveryMac(bad, 1, scheduler), std::invalid_argument);
  EXPECT_THROW(AutoDiscoveryMac(fifteen_seconds(3), 0, scheduler), std::invalid_argument);
}

TEST(AutoDiscoveryMac, HearingAnUnknownNodeWhileWaitingReplansForTheLongerCycle) {
  Network net(day_s(1000));
  AutoDiscoveryMac& mac = net.add(3, fifteen_seconds(4));
  net.start(mac);  // waits for 1020 (30 s grid)
  net.scheduler.run_until(day_s(1005));
  v1::ModemTransmission heard;
  heard.set_src(9);
  mac.on_receive(heard);
  EXPECT_EQ(mac.known_ids(), (std::vector<int32_t>{3, 9}));
  net.scheduler.run_until(day_s(1034));
  EXPECT_TRUE(net.sent.empty());  // not at 1020: the 45 s grid starts at 1035
  net.scheduler.run_until(day_s(1035));
  ASSERT_EQ(net.sent.size(), 1u);
  EXPECT_DOUBLE_EQ(net.sent[0].time(), kDay + 1035.0);
}

}  // namespace
}  // namespace acomms::mac
