// The Iridium driver through the faults of spec §11 on the fake 9603, on
// simulated time. For each: nothing lost (every message reaches the shore,
// after the shore's (MOMSN, payload) dedup), nothing delivered twice, and
// no tight loop of sessions.

#include <gtest/gtest.h>

#include <algorithm>

#include "iridium/mtmsn_window.h"
#include "iridium_test_node.h"

namespace acomms::fake_iridium {
namespace {

// The messages 0..n-1, each exactly once.
void expect_each_once(const std::vector<std::string>& got, int n, size_t size) {
  std::vector<std::string> expected;
  for (int i = 0; i < n; ++i) expected.push_back(message(i, size));
  std::vector<std::string> sorted = got;
  std::sort(sorted.begin(), sorted.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(sorted, expected);
}

// No two session commands closer than `floor` (but those that the driver
// starts at once by design: none in these tests follow a failure sooner).
void expect_spacing(const std::vector<core::Clock::time_point>& starts, std::chrono::seconds floor) {
  for (size_t i = 1; i < starts.size(); ++i) {
    EXPECT_GE(starts[i] - starts[i - 1], floor) << "sessions " << i - 1 << " and " << i;
  }
}

TEST_F(IridiumDriverTest, NoNetworkStopsSessionsUntilServiceReturnsThenSendsOnce) {
  ready();
  vehicle_->modem.set_network(false);
  for (int i = 0; i < 3; ++i) vehicle_->queued.push_back(message(i, 60));
  run_for(1800s);
  // +CIEV:1,0 came first: not one session while the network is gone, only
  // a signal poll every 30 s.
  EXPECT_EQ(vehicle_->modem.session_commands().size(), 1u);
  EXPECT_TRUE(vehicle_->gateway.mo().empty());
  EXPECT_LE(vehicle_->count_command("AT+CSQ"), 1800 / 30 + 1);
  vehicle_->modem.set_network(true);
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 120s)) << vehicle_->modem.transcript();
  expect_each_once(vehicle_->shore_messages(), 3, 60);
}

TEST_F(IridiumDriverTest, StatusThirtyTwoWithoutIndicatorsWaitsForASignalReading) {
  ready();
  // The network goes while a session runs: the change is held (spec §5.3),
  // so the driver learns it from the session's status 32 alone.
  for (int i = 0; i < 2; ++i) vehicle_->queued.push_back(message(i, 60));
  vehicle_->modem.force_status(32, 1);
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 200s)) << vehicle_->modem.transcript();
  EXPECT_GE(vehicle_->count_command("AT+CSQ"), 1);
  expect_each_once(vehicle_->shore_messages(), 2, 60);
}

TEST_F(IridiumDriverTest, AnAntennaFaultIsReportedAndRetriedOnlyEveryFiveMinutes) {
  ready();
  vehicle_->queued.push_back(message(0, 100));
  vehicle_->modem.set_antenna_fault(true);
  run_for(3600s);
  const auto& starts = vehicle_->modem.session_commands();
  EXPECT_LE(starts.size(), 1u + 3600 / 300 + 1);
  expect_spacing({starts.begin() + 1, starts.end()}, std::chrono::seconds(300));
  EXPECT_NE(vehicle_->driver->modem().find("antenna fault"), std::string::npos) << vehicle_->driver->modem();
  vehicle_->modem.set_antenna_fault(false);
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 400s));
  expect_each_once(vehicle_->shore_messages(), 1, 100);
}

TEST_F(IridiumDriverTest, AHungSessionIsRecoveredAndItsMoSentAgainOnce) {
  ready();
  vehicle_->modem.hang_sessions(1);
  for (int i = 0; i < 4; ++i) vehicle_->queued.push_back(message(i, 50));
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 400s)) << vehicle_->modem.transcript();
  EXPECT_EQ(vehicle_->driver->stats().sessions_lost, 1u);
  EXPECT_EQ(vehicle_->driver->stats().mo_resent, 1u);
  EXPECT_EQ(vehicle_->gateway.mo().size(), 1u);  // the hung session sent nothing
  expect_each_once(vehicle_->shore_messages(), 4, 50);
}

TEST_F(IridiumDriverTest, ALostAnswerAfterTheGatewayHasTheMoIsDecidedByTheMomsnAndNotResent) {
  ready();
  vehicle_->modem.lose_answers(1);
  for (int i = 0; i < 4; ++i) vehicle_->queued.push_back(message(i, 50));
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 400s)) << vehicle_->modem.transcript();
  EXPECT_EQ(vehicle_->driver->stats().sessions_lost, 1u);
  EXPECT_EQ(vehicle_->driver->stats().mo_resent, 0u);
  run_for(60s);
  EXPECT_EQ(vehicle_->gateway.mo().size(), 1u);  // one copy: the MOMSN said it went
  expect_each_once(vehicle_->shore_messages(), 4, 50);
}

TEST_F(IridiumDriverTest, AFailureReportedAfterTheGatewayHasTheMoRepeatsTheMomsnSoTheShoreDropsTheCopy) {
  ready();
  vehicle_->modem.fail_at_gateway(1);
  for (int i = 0; i < 4; ++i) vehicle_->queued.push_back(message(i, 50));
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 400s)) << vehicle_->modem.transcript();
  auto mo = vehicle_->gateway.mo();
  ASSERT_EQ(mo.size(), 2u);
  EXPECT_EQ(mo[0].momsn, mo[1].momsn);
  EXPECT_EQ(mo[0].payload, mo[1].payload);
  EXPECT_EQ(vehicle_->driver->stats().sessions_failed, 1u);
  expect_each_once(vehicle_->shore_messages(), 4, 50);
}

TEST_F(IridiumDriverTest, ARebootMidSessionBringsTheModemUpAgainAndResendsTheMo) {
  ready();
  for (int i = 0; i < 4; ++i) vehicle_->queued.push_back(message(i, 50));
  ASSERT_TRUE(run_until([&] { return vehicle_->count_command("AT+SBDIX") >= 2; }, 60s));
  vehicle_->modem.reboot(15s);  // the session dies with the power
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 400s)) << vehicle_->modem.transcript();
  EXPECT_FALSE(vehicle_->modem.echo());  // ATE0 again
  EXPECT_GE(vehicle_->count_command("AT+SBDMTA=1"), 2);
  EXPECT_EQ(vehicle_->gateway.mo().size(), 1u);
  expect_each_once(vehicle_->shore_messages(), 4, 50);
}

TEST_F(IridiumDriverTest, ARebootWhileIdleIsSeenByItsEchoAndTheSettingsComeBack) {
  ready();
  vehicle_->modem.reboot(2s);
  run_for(5s);
  vehicle_->queued.push_back(message(0, 50));
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 200s)) << vehicle_->modem.transcript();
  EXPECT_EQ(vehicle_->driver->stats().resets, 1u);
  EXPECT_FALSE(vehicle_->modem.echo());
  expect_each_once(vehicle_->shore_messages(), 1, 50);
}

TEST_F(IridiumDriverTest, AnMtOfferedTwiceIsDeliveredOnceByItsMtmsn) {
  ready();
  vehicle_->gateway.queue_mt("300234010000001", "only once");
  vehicle_->modem.ring();
  ASSERT_TRUE(run_until([&] { return vehicle_->received.size() == 1; }, 60s));
  vehicle_->modem.repeat_mts(1);
  vehicle_->modem.ring();
  ASSERT_TRUE(run_until([&] { return vehicle_->driver->stats().mt_duplicates == 1; }, 60s))
      << vehicle_->modem.transcript();
  EXPECT_EQ(vehicle_->received.size(), 1u);
}

// A shore endpoint that restarts may number MTs again from a value still
// in the vehicle's window: a new MT under an old number is delivered (the
// shore has counted it delivered); a true repeat (number and payload) is not.
TEST(MtmsnWindow, ANumberSeenBeforeWithAnotherPayloadIsANewMt) {
  drivers::iridium::MtmsnWindow window;
  EXPECT_TRUE(window.admit(17, "go home"));
  EXPECT_FALSE(window.admit(17, "go home")) << "the gateway offered it again";
  EXPECT_TRUE(window.admit(17, "surface now")) << "a restarted shore reused the number";
  for (size_t n = 0; n < drivers::iridium::MtmsnWindow::kSize; ++n) {
    EXPECT_TRUE(window.admit(1000 + static_cast<int>(n), "x"));
  }
  EXPECT_TRUE(window.admit(17, "go home")) << "forgotten after 64 newer MTs";
}

TEST_F(IridiumDriverTest, RepeatedFailuresBackOffToFiveMinutesAndNeverLoopTightly) {
  ready();
  vehicle_->queued.push_back(message(0, 50));
  vehicle_->modem.force_status(18, 1000);  // RF drop, every time
  run_for(3600s);
  const auto& all = vehicle_->modem.session_commands();
  std::vector<core::Clock::time_point> starts(all.begin() + 1, all.end());
  // Four retries at the 10 s floor to 30 s, then every 300 s.
  ASSERT_GE(starts.size(), 5u);
  expect_spacing(starts, std::chrono::seconds(10));
  EXPECT_LE(starts.size(), 4u + 3600 / 300 + 1);
  for (size_t i = 5; i < starts.size(); ++i) EXPECT_GE(starts[i] - starts[i - 1], std::chrono::seconds(300));
  EXPECT_TRUE(vehicle_->gateway.mo().empty());
  EXPECT_EQ(vehicle_->acks, 0);
  // Nothing lost: the frame is still in flight, and goes when the gateway lets it.
  vehicle_->modem.stop_forcing();
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 400s));
  expect_each_once(vehicle_->shore_messages(), 1, 50);
}

TEST_F(IridiumDriverTest, AccessDeniedIsAFaultRetriedEveryHalfHour) {
  ready();
  vehicle_->queued.push_back(message(0, 50));
  vehicle_->modem.force_status(15, 1000);
  run_for(2h);
  const auto& all = vehicle_->modem.session_commands();
  std::vector<core::Clock::time_point> starts(all.begin() + 1, all.end());
  ASSERT_GE(starts.size(), 2u);
  EXPECT_LE(starts.size(), 2u * 3600 / 1800 + 1);
  expect_spacing(starts, std::chrono::seconds(1800));
  EXPECT_NE(vehicle_->driver->modem().find("fault: MO status 15"), std::string::npos) << vehicle_->driver->modem();
  vehicle_->modem.stop_forcing();
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 2000s));
  EXPECT_EQ(vehicle_->driver->modem().find("fault:"), std::string::npos) << vehicle_->driver->modem();
}

TEST_F(IridiumDriverTest, APermanentRefusalOfTheFrameGivesItBackAndItsMessagesGoLater) {
  ready();
  for (int i = 0; i < 3; ++i) vehicle_->queued.push_back(message(i, 50));
  vehicle_->modem.force_status(14, 1);  // invalid segment size: never retry this frame
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 400s)) << vehicle_->modem.transcript();
  EXPECT_EQ(vehicle_->driver->stats().mo_dropped, 1u);
  EXPECT_GE(vehicle_->sent_failed, 1);
  // The modem's MO buffer was cleared (AT+SBDD0) and the frame asked for again.
  EXPECT_GE(vehicle_->data_requests, 2);
  expect_each_once(vehicle_->shore_messages(), 3, 50);
}

}  // namespace
}  // namespace acomms::fake_iridium
