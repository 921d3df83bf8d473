// Real acommsd processes on fake Micro-Modems when things go wrong (issue
// 14's real-daemon guarantees): the port to a modem vanishes and comes
// back, a modem reboots halfway through a packet, the line carries 10 s of
// noise at the full 19200 baud; and the polled MAC's third-party cycle.
// Each time: the daemons keep serving, every queued message reaches the
// other node's subscriber exactly once, and the link status says what
// happened. Node 1 is the vehicle, node 2 the topside, 300 m apart; the
// fake and the drivers run 4x faster than real time (the MAC's slots are
// real seconds).

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <regex>
#include <set>
#include <string>

#include "micromodem_network.h"
#include "stream_subscriber.h"

namespace acomms::testing {
namespace {

using namespace std::chrono_literals;

constexpr double kTimeScale = 4;

// Fixed TDMA, 4 s each: node 1, then node 2.
std::string fixed_mac(int rate) {
  std::string r = std::to_string(rate);
  return "name: \"fixed\" slot { src: 1 rate: " + r + " seconds: 4 } slot { src: 2 rate: " + r + " seconds: 4 }";
}

// How many times each seq was delivered.
std::map<int, int> deliveries(const std::vector<v1::ReceivedMessage>& received) {
  static const std::regex seq_field(R"("seq":\s*(\d+))");
  std::map<int, int> count;
  for (const v1::ReceivedMessage& message : received) {
    std::smatch match;
    if (std::regex_search(message.json(), match, seq_field)) ++count[std::stoi(match[1])];
  }
  return count;
}

bool all_delivered(const std::vector<v1::ReceivedMessage>& received, int first, int last) {
  std::map<int, int> count = deliveries(received);
  for (int seq = first; seq <= last; ++seq) {
    if (count[seq] == 0) return false;
  }
  return true;
}

class MicroModemFaults : public ::testing::Test {
 protected:
  // Both nodes on `mac_1` / `mac_2`, started and serving.
  void start_network(const std::string& name, const std::string& mac_1, const std::string& mac_2) {
    net_ = std::make_unique<MicroModemNetwork>(
        name, std::vector<MicroModemNetwork::Modem>{{1, "1,mm2,300,0,0"}, {2, "2,mm2,0,0,0"}}, kTimeScale);
    ASSERT_TRUE(net_->ok()) << net_->fake_output();
    net_->write_config(1, mac_1);
    net_->write_config(2, mac_2);
    ASSERT_TRUE(net_->start(1)) << net_->daemon_log(1);
    ASSERT_TRUE(net_->start(2)) << net_->daemon_log(2);
  }
  void submit(int from, int to, int first, int last) {
    for (int seq = first; seq <= last; ++seq) {
      grpc::Status status = net_->submit_command(from, to, seq);
      ASSERT_TRUE(status.ok()) << "seq " << seq << ": " << status.error_message();
    }
  }
  // Every seq in first..last delivered exactly once.
  static void expect_each_once(const std::vector<v1::ReceivedMessage>& received, int first, int last) {
    std::map<int, int> count = deliveries(received);
    for (int seq = first; seq <= last; ++seq) EXPECT_EQ(count[seq], 1) << "seq " << seq;
    EXPECT_EQ(received.size(), static_cast<size_t>(last - first + 1));
  }
  std::string logs() { return "\nnode 1:\n" + net_->daemon_log(1) + "\nnode 2:\n" + net_->daemon_log(2); }

  std::unique_ptr<MicroModemNetwork> net_;
};

TEST_F(MicroModemFaults, APortThatVanishesAndComesBackLosesNothingAndDeliversNothingTwice) {
  start_network("mm-port", fixed_mac(1), fixed_mac(1));
  StreamSubscriber vehicle(net_->socket(1), "example.Command");
  submit(2, 1, 1, 3);
  ASSERT_EQ(net_->fault("2 unplug"), "ok");
  // The driver fails, and its restarts fail while the port is away.
  ASSERT_TRUE(wait_until([&] { return net_->link_status(2).driver().failures() >= 2; }, 30s, 200ms)) << logs();
  submit(2, 1, 4, 6);  // the daemon serves meanwhile
  EXPECT_TRUE(net_->daemon(2).running());
  ASSERT_EQ(net_->fault("2 plug"), "ok");
  ASSERT_TRUE(vehicle.wait_for([](const auto& r) { return all_delivered(r, 1, 6); }, 90s)) << logs();
  EXPECT_TRUE(wait_until([&] { return net_->queued(2) == 0; }, 30s, 200ms)) << "the modem's ACKs did not clear it";
  expect_each_once(vehicle.received(), 1, 6);
  v1::LinkStatusResponse status = net_->link_status(2);
  EXPECT_EQ(status.driver().state(), "running");
  EXPECT_GE(status.driver().starts(), 2u) << "the supervisor restarted the driver";
}

TEST_F(MicroModemFaults, AModemResetMidTransmissionLosesNothingAndDeliversNothingTwice) {
  start_network("mm-reset", fixed_mac(5), fixed_mac(5));
  StreamSubscriber vehicle(net_->socket(1), "example.Command");
  submit(2, 1, 1, 4);
  // Halfway through its next data packet: the one carrying these (an empty
  // slot's packet that had already begun is not it).
  ASSERT_EQ(net_->fault("2 reset-mid-tx"), "ok");
  ASSERT_TRUE(vehicle.wait_for([](const auto& r) { return all_delivered(r, 1, 4); }, 90s)) << logs();
  EXPECT_TRUE(wait_until([&] { return net_->queued(2) == 0; }, 60s, 200ms)) << "the modem's ACKs did not clear it";
  expect_each_once(vehicle.received(), 1, 4);
  // The reboot happened during a transmission, which was reported failed;
  // the driver carried on without a restart.
  RunResult raw = net_->raw_log(2);
  ASSERT_EQ(raw.exit_code, 0) << raw.err;
  size_t data_start = raw.out.find(" << $CATXP,");
  while (data_start != std::string::npos && raw.out.compare(data_start, 13, " << $CATXP,2*") == 0) {
    data_start = raw.out.find(" << $CATXP,", data_start + 1);  // mini-packets (ACKs) carry 2
  }
  ASSERT_NE(data_start, std::string::npos) << "node 2 never transmitted data";
  EXPECT_NE(raw.out.find(",INIT,", data_start), std::string::npos) << "no reboot after the first data packet began";
  v1::LinkStatusResponse status = net_->link_status(2);
  EXPECT_GE(status.counters().transmissions_failed(), 1u);
  EXPECT_EQ(status.driver().failures(), 0u) << "a reboot is not a driver failure";
  EXPECT_TRUE(net_->daemon(2).running());
  // The packet had reached the water before the reboot (the fake's choice
  // 23), so the vehicle got it once already: the resend was recognised.
  EXPECT_GE(net_->link_status(1).counters().duplicates_dropped(), 1u);
}

TEST_F(MicroModemFaults, TenSecondsOfNoiseAtFullRateAreCountedShownAndNeverStopTheDaemon) {
  start_network("mm-noise", fixed_mac(1), fixed_mac(1));
  StreamSubscriber vehicle(net_->socket(1), "example.Command");
  ASSERT_EQ(net_->fault("2 noise-for 10"), "ok");  // 1920 bytes/s: 19200 baud, full
  auto end = std::chrono::steady_clock::now() + 10s;
  int seq = 0, answered = 0;
  // Throughout the noise: Submit and LinkStatus answer, each in time.
  wait_until(
      [&] {
        grpc::Status submitted = net_->submit_command(2, 1, ++seq);
        EXPECT_TRUE(submitted.ok()) << submitted.error_message();
        grpc::ClientContext context;
        context.set_deadline(std::chrono::system_clock::now() + 2s);
        v1::LinkStatusResponse response;
        grpc::Status status = api(net_->socket(2))->LinkStatus(&context, v1::LinkStatusRequest(), &response);
        EXPECT_TRUE(status.ok()) << status.error_message();
        answered += status.ok() ? 1 : 0;
        return std::chrono::steady_clock::now() >= end;
      },
      20s, 500ms);
  EXPECT_GE(answered, 4) << "calls spread over the 10 s";
  ASSERT_TRUE(vehicle.wait_for([&](const auto& r) { return all_delivered(r, 1, seq); }, 90s)) << logs();
  expect_each_once(vehicle.received(), 1, seq);

  v1::LinkStatusResponse status = net_->link_status(2);
  const auto& bad = status.counters().bad_input();
  ASSERT_TRUE(bad.contains("noise")) << status.DebugString();
  EXPECT_GE(bad.at("noise"), 5000u) << "bytes outside any sentence";
  uint64_t bad_lines = 0;
  for (const auto& [kind, count] : bad) bad_lines += kind == "noise" ? 0 : count;
  EXPECT_GE(bad_lines, 10u) << status.DebugString();
  EXPECT_EQ(status.driver().failures(), 0u) << "noise is not a driver failure";
  // The raw log shows what came in, noise framed into lines included.
  RunResult raw = net_->raw_log(2);
  ASSERT_EQ(raw.exit_code, 0) << raw.err;
  std::regex noisy_line(R"(Z << \$[^\n]*\\x[0-9A-F]{2})");
  EXPECT_TRUE(std::regex_search(raw.out, noisy_line)) << raw.out.substr(0, 3000);
  RunResult shown = run(ACOMMSCTL_BINARY, {"--socket", net_->socket(2), "link", "status"},
                        (net_->dir() / "status").string());
  EXPECT_NE(shown.out.find("bad input:"), std::string::npos) << shown.out;
}

TEST_F(MicroModemFaults, ThePolledMacsThirdPartyCycleBringsTheVehiclesDataWithLinkFigures) {
  // The topside (2) is the master: its slot polls the vehicle (1) to send
  // to it, at rate 1. The vehicle's own MAC never transmits.
  start_network("mm-polled", "name: \"none\"", "name: \"polled\" slot { src: 1 dest: 2 rate: 1 seconds: 4 }");
  StreamSubscriber topside(net_->socket(2), "example.Command");
  submit(1, 2, 1, 3);
  ASSERT_TRUE(topside.wait_for([](const auto& r) { return all_delivered(r, 1, 3); }, 90s)) << logs();
  EXPECT_TRUE(wait_until([&] { return net_->queued(1) == 0; }, 30s, 200ms)) << "the modem's ACKs did not clear it";
  expect_each_once(topside.received(), 1, 3);
  for (const v1::ReceivedMessage& message : topside.received()) {
    EXPECT_EQ(message.src(), 1);
    EXPECT_EQ(message.link().transmission_src(), 1);
    EXPECT_EQ(message.link().rate(), 1);
    EXPECT_EQ(message.link().packet_type(), 3);  // PSK
    EXPECT_TRUE(message.link().has_snr_in_db());
    EXPECT_TRUE(message.link().has_signal_level_db());
    EXPECT_TRUE(message.link().has_mse_db());
  }
  // On the wire: the master's third-party $CCCYC (ADR1 = the vehicle),
  // Nframes sized for its 4 s slot; the vehicle heard it as a poll.
  RunResult master = net_->raw_log(2);
  std::smatch poll;
  ASSERT_TRUE(std::regex_search(master.out, poll, std::regex(R"(>> \$CCCYC,0,1,2,1,1,(\d)\*)"))) << master.out;
  EXPECT_GE(std::stoi(poll[1]), 1);
  EXPECT_LE(std::stoi(poll[1]), 3);
  RunResult polled = net_->raw_log(1);
  EXPECT_NE(polled.out.find("<< $CACYC,0,1,2,1,1,"), std::string::npos);
  EXPECT_NE(polled.out.find(">> $CCTXD,1,2,1,"), std::string::npos);
}

}  // namespace
}  // namespace acomms::testing
