// The Iridium driver on the fake 9603, simulated time: the bring-up of
// spec §3 in order, MOs packed from the queues and sent, the success as an
// ACK, MTs read and delivered, ring alerts answered with +SBDIXA, MTs still
// queued fetched at once, mailbox checks on their period, garbage and
// unsolicited lines in any state.

#include <gtest/gtest.h>

#include <asio/io_context.hpp>

#include "iridium/at/sbd_binary.h"
#include "link/driver_registry.h"
#include "iridium_test_node.h"

namespace acomms::fake_iridium {
namespace {

TEST_F(IridiumDriverTest, BringsTheModemUpInTheSpecsOrderThenChecksTheMailbox) {
  ready();
  const std::vector<std::string> expected = {
      "AT",           "ATE0",           "ATV1",        "ATQ0",         "AT&K0",    "AT*R1",
      "AT+CIER=1,1,1,1", "AT+SBDMTA=1", "AT+SBDAREG=1", "AT+CGSN",     "AT+SBDSX", "AT+SBDD2",
      "AT+SBDSX",     "AT+SBDIX"};
  auto commands = vehicle_->host_commands();
  ASSERT_GE(commands.size(), expected.size());
  EXPECT_EQ(std::vector<std::string>(commands.begin(), commands.begin() + expected.size()), expected);
  EXPECT_TRUE(vehicle_->driver->ready());
  EXPECT_EQ(vehicle_->driver->imei(), "300234010000001");
  EXPECT_FALSE(vehicle_->modem.echo());
  EXPECT_EQ(vehicle_->driver->stats().mailbox_checks, 1u);
  EXPECT_EQ(vehicle_->modem.momsn(), 42);  // the mailbox check used 41
  EXPECT_NE(vehicle_->driver->modem().find("signal 3/5"), std::string::npos) << vehicle_->driver->modem();
}

TEST_F(IridiumDriverTest, RefusesAModemWithAnotherImei) {
  v1::DriverConfig config;
  config.mutable_iridium()->set_imei("300234010999999");
  make({}, config);
  vehicle_->start();
  EXPECT_THROW(run_for(30s), link::DriverError);
}

TEST_F(IridiumDriverTest, PacksQueuedMessagesIntoOneMoAndAcknowledgesItOnSuccess) {
  ready();
  for (int i = 0; i < 8; ++i) vehicle_->queued.push_back(message(i, 40));
  const std::string before = vehicle_->written;
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1; }, 120s)) << vehicle_->modem.transcript();
  EXPECT_EQ(vehicle_->max_num_frames, 1u);
  EXPECT_EQ(vehicle_->max_frame_bytes, 340u);
  auto mo = vehicle_->gateway.mo();
  ASSERT_EQ(mo.size(), 1u);
  EXPECT_EQ(mo[0].payload.size(), 320u);  // 8 messages of 40 bytes in one MO
  EXPECT_EQ(mo[0].momsn, 42);
  // The host's bytes: the command, the payload and its checksum, then the session.
  std::string payload = mo[0].payload;
  const std::string wrote = vehicle_->written.substr(before.size());
  const uint16_t sum = ::acomms::iridium::sbd_checksum(payload);
  const std::string block = payload + static_cast<char>(sum >> 8) + static_cast<char>(sum & 0xff);
  EXPECT_NE(wrote.find("AT+SBDWB=320\r" + block + "AT+SBDSX\r"), std::string::npos);
  // A success leaves the MO in the buffer: the driver clears it (spec §4.6).
  ASSERT_TRUE(run_until([&] { return vehicle_->count_command("AT+SBDD0") >= 1; }, 10s));
  EXPECT_TRUE(vehicle_->queued.empty());
  EXPECT_TRUE(vehicle_->in_flight.empty());
  EXPECT_EQ(vehicle_->sent_ok, 1);
  EXPECT_EQ(vehicle_->driver->stats().mo_sent, 1u);
  // The next mailbox check does not send it again.
  run_for(400s);
  EXPECT_EQ(vehicle_->gateway.mo().size(), 1u);
  EXPECT_GE(vehicle_->driver->stats().mailbox_checks, 2u);
}

TEST_F(IridiumDriverTest, MoreThanOneMoOfMessagesGoesInBackToBackSessions) {
  ready();
  for (int i = 0; i < 20; ++i) vehicle_->queued.push_back(message(i, 50));
  ASSERT_TRUE(run_until([&] { return vehicle_->shore_messages().size() == 20; }, 600s));
  auto mo = vehicle_->gateway.mo();
  ASSERT_EQ(mo.size(), 4u);  // 6 of 50 bytes fit 340: 6, 6, 6, 2
  EXPECT_EQ(mo[0].payload.size(), 300u);
  EXPECT_EQ(mo[3].payload.size(), 100u);
}

TEST_F(IridiumDriverTest, AnMtIsReadAndDeliveredAsDataFromTheShore) {
  ready();
  vehicle_->gateway.queue_mt("300234010000001", "ping 0001");
  ASSERT_TRUE(run_until([&] { return !vehicle_->received.empty(); }, 400s)) << vehicle_->modem.transcript();
  const ModemTransmission& rx = vehicle_->received[0];
  EXPECT_EQ(rx.type(), ModemTransmission::DATA);
  EXPECT_EQ(rx.src(), Vehicle::kShore);
  EXPECT_EQ(rx.dest(), Vehicle::kId);
  ASSERT_EQ(rx.frame_size(), 1);
  EXPECT_EQ(rx.frame(0), "ping 0001");
  EXPECT_FALSE(rx.ack_requested());
  EXPECT_EQ(vehicle_->count_command("AT+SBDRB"), 1);
}

TEST_F(IridiumDriverTest, ARingAlertIsAnsweredWithSbdixaAndBothPrefixesAreAccepted) {
  for (bool ixa_prefix : {true, false}) {
    FakeSbdConfig modem;
    modem.ixa_prefix = ixa_prefix;
    ready(modem);
    vehicle_->gateway.queue_mt("300234010000001", "cmd");
    vehicle_->modem.ring();
    // Well before the 300 s mailbox check.
    ASSERT_TRUE(run_until([&] { return !vehicle_->received.empty(); }, 60s)) << vehicle_->modem.transcript();
    EXPECT_EQ(vehicle_->count_command("AT+SBDIXA"), 1);
    EXPECT_EQ(vehicle_->received[0].frame(0), "cmd");
    EXPECT_EQ(vehicle_->driver->stats().ring_alerts, 1u);
  }
}

TEST_F(IridiumDriverTest, MtsStillQueuedAtTheGatewayAreFetchedAtOnce) {
  ready();
  for (int i = 0; i < 3; ++i) vehicle_->gateway.queue_mt("300234010000001", "mt" + std::to_string(i));
  vehicle_->modem.ring();
  ASSERT_TRUE(run_until([&] { return vehicle_->received.size() == 3; }, 150s)) << vehicle_->modem.transcript();
  for (int i = 0; i < 3; ++i) EXPECT_EQ(vehicle_->received[i].frame(0), "mt" + std::to_string(i));
}

TEST_F(IridiumDriverTest, ChecksTheMailboxEveryMailboxCheckSeconds) {
  v1::DriverConfig config;
  config.mutable_iridium()->set_mailbox_check_s(120);
  ready({}, config);
  const uint64_t first = vehicle_->driver->stats().mailbox_checks;
  run_for(1210s);
  // One every 120 s after each session's end (each takes 20 s): 8 in 1210 s.
  EXPECT_EQ(vehicle_->driver->stats().mailbox_checks - first, 8u);
}

TEST_F(IridiumDriverTest, GarbageAndUnsolicitedLinesInEveryStateChangeNothing) {
  make();
  vehicle_->port->set_noise(std::string("\xff\xfe\x01junk\r\n+CIEV:0,4\r\n+SBDIX: 1, 2\r\n", 34));
  vehicle_->start();
  ASSERT_TRUE(run_until([&] { return vehicle_->driver->ready(); }, 60s)) << vehicle_->modem.transcript();
  for (int i = 0; i < 4; ++i) vehicle_->queued.push_back(message(i, 30));
  vehicle_->gateway.queue_mt("300234010000001", "through the noise");
  ASSERT_TRUE(run_until([&] { return vehicle_->acks == 1 && !vehicle_->received.empty(); }, 400s))
      << vehicle_->modem.transcript();
  EXPECT_EQ(vehicle_->received[0].frame(0), "through the noise");
  EXPECT_EQ(vehicle_->shore_messages().size(), 4u);
  auto counters = vehicle_->driver->counters();
  EXPECT_GT(counters.bad_input["garbled line"], 10u);
  EXPECT_GT(counters.bad_input["malformed answer"], 10u);
  EXPECT_EQ(vehicle_->driver->rssi(), 4);  // the last +CIEV:0,4 heard
}

TEST_F(IridiumDriverTest, AMacRequestIsRefusedWithTheReason) {
  ready();
  ModemTransmission tx;
  tx.set_type(ModemTransmission::DATA);
  tx.set_src(Vehicle::kId);
  vehicle_->driver->initiate_transmission(tx);
  EXPECT_EQ(vehicle_->sent_failed, 1);
}

}  // namespace
}  // namespace acomms::fake_iridium

namespace acomms::fake_iridium {
namespace {

TEST(IridiumDriverConfigTest, RegistersByNameAndRefusesBadSettingsNamingTheField) {
  const link::DriverRegistry& registry = link::DriverRegistry::linked();
  core::SimulatedScheduler scheduler(core::Clock::time_point(std::chrono::seconds(1'700'000'000)));
  asio::io_context io;
  v1::DriverConfig config;
  config.set_name("iridium");
  config.mutable_iridium()->set_port("tcp:127.0.0.1:1");
  EXPECT_THROW(registry.create("iridium", {config, scheduler}), std::invalid_argument);  // no event loop
  auto refusal = [&](const v1::DriverConfig& c) {
    try {
      registry.create("iridium", {c, scheduler, &io});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refusal(config).find("driver.iridium.shore_id"), std::string::npos) << refusal(config);
  config.mutable_iridium()->set_shore_id(1);  // modem_id unset means 1: the shore cannot be us
  EXPECT_NE(refusal(config).find("own modem_id 1"), std::string::npos) << refusal(config);
  config.set_modem_id(2);
  config.mutable_iridium()->set_max_mo_bytes(341);
  EXPECT_NE(refusal(config).find("driver.iridium.max_mo_bytes"), std::string::npos) << refusal(config);
  config.mutable_iridium()->set_max_mo_bytes(0);
  config.mutable_iridium()->set_imei("30023401");
  EXPECT_NE(refusal(config).find("driver.iridium.imei"), std::string::npos) << refusal(config);
  config.mutable_iridium()->clear_imei();
  config.mutable_iridium()->clear_port();
  EXPECT_NE(refusal(config).find("driver.iridium.port"), std::string::npos) << refusal(config);
  config.mutable_iridium()->set_port("tcp:127.0.0.1:1");
  EXPECT_EQ(refusal(config), "accepted");
}

}  // namespace
}  // namespace acomms::fake_iridium
