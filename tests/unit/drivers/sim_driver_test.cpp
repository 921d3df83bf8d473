// The simulator's physics on the simulated scheduler, with exact times.
// Geometry: 1500 m at 1500 m/s is exactly 1 s; a rate-0 packet with one
// frame is 3.5 s in the water; a mini-packet (poll, ACK) 0.7 s; the
// turnaround before an ACK or a poll answer 0.5 s.
#include "sim/sim_driver.h"

#include <gtest/gtest.h>

#include "link/rate_table.h"
#include "sim/navigation_position.h"
#include "sim_test_node.h"

namespace acomms::drivers {
namespace {

using core::Clock;
using std::chrono::milliseconds;
using std::chrono::seconds;
using testing::TestNode;
using v1::ModemTransmission;

class SimDriverTest : public ::testing::Test {
 protected:
  SimDriverTest() : t0_(Clock::time_point(seconds(1'700'000'000))), scheduler_(t0_) {}
  Clock::time_point at(milliseconds ms) const { return t0_ + ms; }

  Clock::time_point t0_;
  core::SimulatedScheduler scheduler_;
  std::shared_ptr<SimChannel> channel_ = SimChannel::create(42);
};

TEST_F(SimDriverTest, ArrivesAfterRangeOverSoundSpeedPlusAirTime) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500);
  a.send(2, {"hello"}, 0, /*ack=*/false);
  ASSERT_EQ(a.requests.size(), 1u);
  EXPECT_EQ(a.requests[0].max_num_frames(), 1u);  // rate 0: 1 x 32 bytes
  EXPECT_EQ(a.requests[0].max_frame_bytes(), 32u);

  scheduler_.run_until(at(milliseconds(4499)));
  EXPECT_TRUE(b.received.empty());
  ASSERT_EQ(a.results.size(), 1u);  // went out once all in the water: 3.5 s
  EXPECT_TRUE(a.results[0].ok) << a.results[0].error;
  EXPECT_EQ(a.results[0].at, at(milliseconds(3500)));

  scheduler_.run_until(at(milliseconds(4500)));
  ASSERT_EQ(b.received.size(), 1u);
  const auto& rx = b.received[0];
  EXPECT_EQ(rx.at, at(milliseconds(4500)));  // 1 s + 3.5 s
  EXPECT_DOUBLE_EQ(rx.tx.time(), 1'700'000'004.5);
  EXPECT_EQ(rx.tx.src(), 1);
  EXPECT_EQ(rx.tx.dest(), 2);
  ASSERT_EQ(rx.tx.frame_size(), 1);
  EXPECT_EQ(rx.tx.frame(0), "hello");
  EXPECT_NE(rx.tx.link_quality().find("range_m=1500.0"), std::string::npos);
  EXPECT_EQ(b.driver->stats().received, 1u);
}

// A moving vehicle: the node's position comes from its navigation input
// (core::NodePosition, fed by SubmitNavigation, as sim_plugin.cpp wires it),
// so the range, and the
// arrival time, follow the newest fix.
TEST_F(SimDriverTest, PositionSourceMovesTheNodeForLaterTransmissions) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500);
  core::NodePosition navigation;
  a.driver->set_position_source(std::make_shared<NavigationPosition>(&navigation, a.driver->position()));
  EXPECT_EQ(a.driver->position().x, 0);  // no fix yet: the config's position
  navigation.set(core::NodeFix{1'700'000'000, 1500, 1500, -20});
  EXPECT_EQ(a.driver->position().y, 1500);
  EXPECT_EQ(a.driver->position().z, -20);
  a.send(2, {"moved"}, 0, /*ack=*/false);
  scheduler_.run_until(at(milliseconds(4499)));
  EXPECT_TRUE(b.received.empty());  // 1500.1 m away now, not 0
  scheduler_.run_until(at(milliseconds(4501)));
  ASSERT_EQ(b.received.size(), 1u);
  EXPECT_NE(b.received[0].tx.link_quality().find("range_m=1500.1"), std::string::npos)
      << b.received[0].tx.link_quality();
}

TEST_F(SimDriverTest, SoundSpeedAndRateSetTheTimes) {
  v1::DriverConfig slow;
  slow.mutable_sim()->set_sound_speed(1000);
  TestNode a(scheduler_, channel_, 1, 0, 0, slow), b(scheduler_, channel_, 2, 0, 2000, slow);
  // Rate 5 with 2 of its 8 frames: 0.3 s + 2 x 2048 bits / 5300 bps.
  a.send(2, {std::string(256, 'x'), std::string(10, 'y')}, 5, false);
  auto air = link::packet_air_time(*link::find_rate(5), 2);
  scheduler_.run_until(t0_ + seconds(10));
  ASSERT_EQ(b.received.size(), 1u);
  EXPECT_EQ(b.received[0].at, t0_ + seconds(2) + air);
}

TEST_F(SimDriverTest, AckRoundTripListsTheFramesAndIsReportedOnlyToTheSender) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500), c(scheduler_, channel_, 3, 0, 1500);
  a.send(2, {"frame0"});
  scheduler_.run_until(t0_ + seconds(20));
  ASSERT_EQ(b.received.size(), 1u);
  // B answers 0.5 s after the end (4.5 s); the 0.7 s ACK takes 1 s back.
  ASSERT_EQ(a.received.size(), 1u);
  const auto& ack = a.received[0];
  EXPECT_EQ(ack.at, at(milliseconds(4500 + 500 + 700 + 1000)));
  EXPECT_EQ(ack.tx.type(), ModemTransmission::ACK);
  EXPECT_EQ(ack.tx.src(), 2);
  EXPECT_EQ(ack.tx.dest(), 1);
  ASSERT_EQ(ack.tx.acked_frame_size(), 1);
  EXPECT_EQ(ack.tx.acked_frame(0), 0u);
  // C hears the DATA (for anyone; the queues filter by dest) but sends no
  // ACK, and is not told about B's ACK to A.
  ASSERT_EQ(c.received.size(), 1u);
  EXPECT_EQ(c.received[0].tx.type(), ModemTransmission::DATA);
  EXPECT_EQ(c.driver->stats().sent, 0u);
  EXPECT_TRUE(b.results.empty());  // ACKs are the driver's own business
}

TEST_F(SimDriverTest, BroadcastAndNoAckRequestedGetNoAck) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500);
  a.send(0, {"to all"});
  scheduler_.run_until(t0_ + seconds(5));
  a.send(2, {"no ack"}, 0, false);
  scheduler_.run_until(t0_ + seconds(20));
  EXPECT_EQ(b.received.size(), 2u);
  EXPECT_TRUE(a.received.empty());
  EXPECT_EQ(b.driver->stats().sent, 0u);
}

TEST_F(SimDriverTest, PollMakesThePolledNodeSendItsData) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500);
  b.next_frames.push_back({"from B"});
  ModemTransmission poll;
  poll.set_src(2);  // not us: ask node 2 to send
  poll.set_dest(1);
  poll.set_rate(0);
  a.driver->initiate_transmission(poll);
  EXPECT_TRUE(a.requests.empty());  // the poller asks its queues nothing

  scheduler_.run_until(t0_ + seconds(20));
  ASSERT_EQ(a.results.size(), 1u);
  EXPECT_TRUE(a.results[0].ok);
  EXPECT_EQ(a.results[0].at, at(milliseconds(700)));  // a mini-packet
  // B hears the poll at 1.7 s, asks its queues at 2.2 s...
  ASSERT_EQ(b.requests.size(), 1u);
  EXPECT_EQ(b.requests[0].src(), 2);
  EXPECT_EQ(b.requests[0].dest(), 1);
  EXPECT_EQ(b.requests[0].max_frame_bytes(), 32u);
  ASSERT_EQ(b.results.size(), 1u);
  EXPECT_EQ(b.results[0].at, at(milliseconds(2200 + 3500)));
  // ...and A has B's data at 2.2 + 1 + 3.5 s; the poll itself is not reported.
  ASSERT_EQ(a.received.size(), 1u);
  EXPECT_EQ(a.received[0].at, at(milliseconds(6700)));
  EXPECT_EQ(a.received[0].tx.src(), 2);
  EXPECT_EQ(a.received[0].tx.frame(0), "from B");
  // A acknowledges B's data: B has the ACK at 6.7 + 0.5 + 0.7 + 1 s.
  ASSERT_EQ(b.received.size(), 1u);
  EXPECT_EQ(b.received[0].tx.type(), ModemTransmission::ACK);
  EXPECT_EQ(b.received[0].at, at(milliseconds(8900)));
}

TEST_F(SimDriverTest, HalfDuplexNodesCannotHearWhileTransmitting) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500);
  // Both at once: each packet reaches the other [1, 4.5] s while it sends [0, 3.5] s.
  a.send(2, {"a"}, 0, false);
  b.send(1, {"b"}, 0, false);
  scheduler_.run_until(t0_ + seconds(10));
  EXPECT_TRUE(a.received.empty());
  EXPECT_TRUE(b.received.empty());
  EXPECT_EQ(a.driver->stats().lost_half_duplex, 1u);
  EXPECT_EQ(b.driver->stats().lost_half_duplex, 1u);
}

TEST_F(SimDriverTest, APacketWhoseStartWasMissedIsLostEvenAfterTransmitting) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500), c(scheduler_, channel_, 3, -1500);
  a.send(2, {"a"}, 0, false);  // reaches B over [1, 4.5] s
  scheduler_.run_until(at(milliseconds(500)));
  ModemTransmission poll;  // B sends a 0.7 s poll over [0.5, 1.2] s
  poll.set_src(3);
  poll.set_rate(0);
  b.driver->initiate_transmission(poll);
  scheduler_.run_until(t0_ + seconds(30));
  EXPECT_TRUE(std::none_of(b.received.begin(), b.received.end(),
                           [](const auto& h) { return h.tx.src() == 1; }));
  EXPECT_EQ(b.driver->stats().lost_half_duplex, 1u);
}

TEST_F(SimDriverTest, StartingToTransmitMidPacketLosesIt) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500);
  a.send(2, {"a"}, 0, false);  // reaches B over [1, 4.5] s
  scheduler_.run_until(at(milliseconds(2000)));
  b.send(0, {"b"}, 0, false);
  scheduler_.run_until(t0_ + seconds(10));
  EXPECT_TRUE(b.received.empty());
  EXPECT_EQ(b.driver->stats().lost_half_duplex, 1u);
}

TEST_F(SimDriverTest, OverlappingPacketsCollideAtTheReceiver) {
  TestNode a(scheduler_, channel_, 1, -1500), b(scheduler_, channel_, 2, 0), c(scheduler_, channel_, 3, 1500);
  a.send(2, {"a"}, 0, false);
  scheduler_.run_until(at(milliseconds(1000)));
  c.send(2, {"c"}, 0, false);  // at B: A over [1, 4.5] s, C over [2, 5.5] s
  scheduler_.run_until(t0_ + seconds(10));
  EXPECT_TRUE(b.received.empty());
  EXPECT_EQ(b.driver->stats().lost_collision, 2u);
}

TEST_F(SimDriverTest, CountersReportHalfDuplexAndCollisionLossesForLinkStatus) {
  TestNode a(scheduler_, channel_, 1, -1500), b(scheduler_, channel_, 2, 0), c(scheduler_, channel_, 3, 1500);
  a.send(2, {"a"}, 0, false);
  scheduler_.run_until(at(milliseconds(1000)));
  c.send(2, {"c"}, 0, false);  // at B: A over [1, 4.5] s, C over [2, 5.5] s: both collide
  scheduler_.run_until(at(milliseconds(10000)));
  // B transmits over [10, 13.5] s while A's next reaches it over [11, 14.5] s.
  a.send(2, {"a2"}, 0, false);
  scheduler_.run_until(at(milliseconds(11000)));
  b.send(1, {"b"}, 0, false);
  scheduler_.run_until(t0_ + seconds(30));
  link::DriverCounters counters = b.driver->counters();
  EXPECT_EQ(counters.lost_collision, 2u);
  EXPECT_EQ(counters.lost_half_duplex, 1u);
  EXPECT_EQ(counters.lost_collision, b.driver->stats().lost_collision);
  EXPECT_EQ(counters.lost_half_duplex, b.driver->stats().lost_half_duplex);
  EXPECT_TRUE(b.received.empty());
}

TEST_F(SimDriverTest, TimingForTheSlotBudgetIsTheSimulatorsOwnExactly) {
  TestNode a(scheduler_, channel_, 1, 0);
  EXPECT_EQ(a.driver->packet_air_time(5, 8), link::packet_air_time(*link::find_rate(5), 8));
  EXPECT_EQ(a.driver->packet_air_time(0, 1), milliseconds(3500));
  EXPECT_EQ(a.driver->ack_time(5), milliseconds(500 + 700));
  EXPECT_EQ(a.driver->sound_speed(), 1500);
}

TEST_F(SimDriverTest, BackToBackPacketsDoNotCollide) {
  TestNode a(scheduler_, channel_, 1, -1500), b(scheduler_, channel_, 2, 0), c(scheduler_, channel_, 3, 1500);
  a.send(2, {"a"}, 0, false);
  scheduler_.run_until(at(milliseconds(3500)));
  c.send(2, {"c"}, 0, false);  // at B: [1, 4.5] s then [4.5, 8] s
  scheduler_.run_until(t0_ + seconds(10));
  ASSERT_EQ(b.received.size(), 2u);
  EXPECT_EQ(b.received[0].at, at(milliseconds(4500)));
  EXPECT_EQ(b.received[1].at, at(milliseconds(8000)));
}

// Sends `n` packets A -> B, spaced so that nothing collides; returns when each that arrived did.
std::vector<Clock::time_point> arrivals(double loss, double max_range, double range, int n, uint32_t seed) {
  core::SimulatedScheduler scheduler(Clock::time_point(seconds(1'700'000'000)));
  auto channel = SimChannel::create(seed);
  v1::DriverConfig config;
  config.mutable_sim()->set_loss_probability(loss);
  config.mutable_sim()->set_max_range_m(max_range);
  TestNode a(scheduler, channel, 1, 0, 0, config), b(scheduler, channel, 2, range, 0, config);
  for (int i = 0; i < n; ++i) {
    a.send(2, {"x"}, 0, false);
    scheduler.run_for(seconds(10));
  }
  scheduler.run_for(seconds(60));  // the last ones still in the water
  std::vector<Clock::time_point> out;
  for (const auto& heard : b.received) out.push_back(heard.at);
  return out;
}

size_t delivered(double loss, double max_range, double range, int n, uint32_t seed) {
  return arrivals(loss, max_range, range, n, seed).size();
}

TEST_F(SimDriverTest, FixedLossMatchesItsProbabilityAndIsDeterministic) {
  auto got = arrivals(0.3, 0, 1500, 2000, 7);
  EXPECT_NEAR(static_cast<double>(got.size()) / 2000, 0.7, 0.04);
  EXPECT_EQ(arrivals(0.3, 0, 1500, 2000, 7), got);  // same seed, same packets lost
  EXPECT_NE(arrivals(0.3, 0, 1500, 2000, 8), got);  // another seed, other packets
}

TEST_F(SimDriverTest, RangeLossCombinesWithFixedLoss) {
  v1::DriverConfig config;
  config.mutable_sim()->set_loss_probability(0.2);
  config.mutable_sim()->set_max_range_m(3000);
  TestNode a(scheduler_, channel_, 1, 0, 0, config);
  EXPECT_DOUBLE_EQ(a.driver->loss_probability(0), 0.2);
  EXPECT_DOUBLE_EQ(a.driver->loss_probability(1500), 1 - 0.8 * 0.5);
  EXPECT_DOUBLE_EQ(a.driver->loss_probability(3000), 1);
  EXPECT_DOUBLE_EQ(a.driver->loss_probability(9000), 1);
  EXPECT_NEAR(static_cast<double>(delivered(0.2, 3000, 1500, 2000, 3)) / 2000, 0.4, 0.04);
  EXPECT_EQ(delivered(0, 3000, 3000, 50, 3), 0u);  // at max range: never
  EXPECT_EQ(delivered(0, 0, 30000, 50, 3), 50u);   // no loss configured: always
}

TEST_F(SimDriverTest, FrameLimitsAndBadRequestsAreReportedNotSent) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500);
  a.send(2, {"1", "2"}, 0);  // rate 0 takes one frame
  a.send(2, {std::string(33, 'x')}, 0);
  a.send(2, {}, 0);
  a.send(2, {"x"}, 9);  // refused before the data request
  ASSERT_EQ(a.results.size(), 4u);
  for (const auto& r : a.results) EXPECT_FALSE(r.ok);
  EXPECT_NE(a.results[0].error.find("gave 2 frames, rate 0 allows 1"), std::string::npos);
  EXPECT_NE(a.results[1].error.find("33 bytes"), std::string::npos);
  EXPECT_NE(a.results[2].error.find("nothing to send"), std::string::npos);
  EXPECT_NE(a.results[3].error.find("rate 9 is not in 0..5"), std::string::npos);
  EXPECT_EQ(a.driver->stats().sent, 0u);
}

TEST_F(SimDriverTest, BusyModemRefusesASecondTransmission) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500);
  a.send(2, {"first"}, 0, false);
  a.send(2, {"second"}, 0, false);
  ASSERT_EQ(a.results.size(), 1u);
  EXPECT_FALSE(a.results[0].ok);
  EXPECT_NE(a.results[0].error.find("busy transmitting"), std::string::npos) << a.results[0].error;
  scheduler_.run_until(t0_ + seconds(10));
  EXPECT_EQ(b.received.size(), 1u);
}

TEST_F(SimDriverTest, StoppedNodeHearsNothingAndGetsNoCallbacks) {
  TestNode a(scheduler_, channel_, 1, 0), b(scheduler_, channel_, 2, 1500);
  EXPECT_EQ(channel_->size(), 2u);
  a.send(2, {"x"});
  b.driver->stop();
  a.driver->stop();
  EXPECT_EQ(channel_->size(), 0u);
  scheduler_.run_until(t0_ + seconds(20));
  EXPECT_TRUE(b.received.empty());
  EXPECT_TRUE(a.results.empty());
  EXPECT_EQ(scheduler_.pending(), 0u);
  ModemTransmission tx;
  EXPECT_THROW(a.driver->initiate_transmission(tx), link::DriverError);
}

TEST_F(SimDriverTest, BadConfigIsRejectedNamingTheField) {
  v1::DriverConfig config;
  config.mutable_sim()->set_loss_probability(1.5);
  try {
    SimDriver driver(config, scheduler_, channel_);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("driver.sim.loss_probability"), std::string::npos);
  }
  v1::DriverConfig loopback;
  loopback.mutable_sim()->set_listen("127.0.0.1:0");
  EXPECT_THROW(SimDriver(loopback, scheduler_, nullptr), std::invalid_argument);  // no event loop
}

TEST_F(SimDriverTest, AloneNodeTransmitsIntoTheVoid) {
  v1::DriverConfig config;
  SimDriver alone(config, scheduler_, static_cast<asio::io_context*>(nullptr));
  std::vector<bool> results;
  link::DriverCallbacks callbacks;
  callbacks.on_data_request = [](ModemTransmission* tx) { tx->add_frame(std::string("x")); };
  callbacks.on_transmit_result = [&](const ModemTransmission&, bool ok, const std::string&) {
    results.push_back(ok);
  };
  alone.start(callbacks);
  ModemTransmission tx;
  tx.set_src(1);
  alone.initiate_transmission(tx);
  scheduler_.run_until(t0_ + seconds(5));
  EXPECT_EQ(results, std::vector<bool>{true});
}

}  // namespace
}  // namespace acomms::drivers
