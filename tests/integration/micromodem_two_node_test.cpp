// Two real acommsd processes, each on its own fake Micro-Modem (one
// fake_micromodem process, two modems in one water, 300 m apart, on TCP
// ports like serial-to-TCP gateways), with fixed TDMA: a Command submitted
// on the topside (node 2) reaches the vehicle's (node 1) subscriber with the
// modem's link figures, and the modem's own ACK clears the topside's queue.
// The figures are kept with the message: replayed from the store (Subscribe
// after: 0), in Events, and in `acommsctl events`, they are the live ones.
// Once at rate 0 (FSK) and once at rate 5 (PSK). The fake and the drivers
// run 4x faster than real time (micromodem_network.h); the MAC's slots are
// real seconds.
#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "micromodem_network.h"
#include "stream_subscriber.h"

namespace acomms::testing {
namespace {

using namespace std::chrono_literals;

constexpr double kTimeScale = 4;

class MicroModemTwoNode : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    net_ = std::make_unique<MicroModemNetwork>(
        "mm-two-node-" + std::to_string(GetParam()),
        std::vector<MicroModemNetwork::Modem>{{1, "1,mm2,300,0,0"}, {2, "2,mm2,0,0,0"}}, kTimeScale);
    ASSERT_TRUE(net_->ok()) << net_->fake_output();
    std::string rate = std::to_string(GetParam());
    std::string mac = "name: \"fixed\" slot { src: 1 rate: " + rate + " seconds: 4 } slot { src: 2 rate: " + rate +
                      " seconds: 4 }";
    for (int id : {1, 2}) net_->write_config(id, mac);
    for (int id : {1, 2}) ASSERT_TRUE(net_->start(id)) << net_->daemon_log(id);
  }
  void TearDown() override {
    // Both daemons stop cleanly (the network's destructor only signals them).
    for (int id : {1, 2}) {
      if (!net_ || !net_->daemon(id).running()) continue;
      net_->daemon(id).signal(SIGTERM);
      EXPECT_EQ(net_->daemon(id).wait(15s), std::optional<int>(0)) << "node " << id << ":\n" << net_->daemon_log(id);
    }
  }

  std::unique_ptr<MicroModemNetwork> net_;
};

TEST_P(MicroModemTwoNode, ACommandReachesTheVehicleWithLinkFiguresAndTheModemsAckClearsTheQueue) {
  StreamSubscriber vehicle(net_->socket(1), "example.Command");
  grpc::Status submitted = net_->submit_command(2, 1, 7);
  ASSERT_TRUE(submitted.ok()) << submitted.error_message();

  bool heard = vehicle.wait_for([](const auto& received) { return !received.empty(); }, 60s);
  bool cleared = heard && wait_until([&] { return net_->queued(2) == 0; }, 30s, 200ms);
  ASSERT_TRUE(heard) << "vehicle:\n" << net_->daemon_log(1) << "\ntopside:\n" << net_->daemon_log(2);
  const v1::ReceivedMessage command = vehicle.received().front();
  EXPECT_EQ(command.src(), 2);
  EXPECT_EQ(command.dest(), 1);
  EXPECT_EQ(command.link().transmission_src(), 2);
  EXPECT_EQ(command.link().rate(), GetParam());
  EXPECT_TRUE(command.link().has_snr_in_db());
  EXPECT_TRUE(command.link().has_signal_level_db());
  EXPECT_EQ(command.link().packet_type(), GetParam() == 0 ? 1 : 3);  // FSK, PSK
  EXPECT_TRUE(cleared) << "the modem's ACK did not clear the topside's queue:\n" << net_->daemon_log(2);
  EXPECT_GE(net_->link_status(1).counters().receptions_with_figures(), 1u);
  EXPECT_GE(net_->link_status(2).counters().acks_received(), 1u);
  EXPECT_EQ(net_->link_status(1).driver().modem(), "MM2 2.0.27087") << "the revision its $CAREV gave";
  // The raw link log, through acommsctl: the vehicle's start-up set SRC 1.
  RunResult raw = net_->raw_log(1);
  EXPECT_EQ(raw.exit_code, 0) << raw.err;
  EXPECT_NE(raw.out.find(" >> $CCCFG,SRC,1*"), std::string::npos) << raw.out.substr(0, 2000);
  EXPECT_NE(raw.out.find(" << $CACFG,SRC,1*"), std::string::npos);

  // Kept with the message in the vehicle's event log: a replay from the
  // store carries the figures it carried live.
  using google::protobuf::util::MessageDifferencer;
  StreamSubscriber replay(net_->socket(1), "example.Command", 0);
  ASSERT_TRUE(replay.wait_for([](const auto& received) { return !received.empty(); }, 30s));
  const v1::ReceivedMessage replayed = replay.received().front();
  EXPECT_EQ(replayed.seq(), command.seq());
  EXPECT_TRUE(replayed.has_link());
  EXPECT_TRUE(MessageDifferencer::Equals(replayed.link(), command.link()))
      << "live:\n" << command.link().DebugString() << "replayed:\n" << replayed.link().DebugString();

  // And in `acommsctl events`: --json has them as the API's "link", the
  // table shows who sent it, the rate, the packet type and the SNR.
  const std::vector<std::string> received_events = {"--socket", net_->socket(1), "events", "--kind", "received"};
  std::vector<std::string> as_json = received_events;
  as_json.push_back("--json");
  RunResult json = run(ACOMMSCTL_BINARY, as_json, (net_->dir() / "events-json").string());
  ASSERT_EQ(json.exit_code, 0) << json.err;
  v1::EventsResponse events;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(json.out, &events).ok()) << json.out;
  ASSERT_EQ(events.events_size(), 1) << json.out;
  EXPECT_TRUE(MessageDifferencer::Equals(events.events(0).link(), command.link())) << json.out;
  RunResult table = run(ACOMMSCTL_BINARY, received_events, (net_->dir() / "events-text").string());
  ASSERT_EQ(table.exit_code, 0) << table.err;
  const std::string how = "tx 2 rate " + std::to_string(GetParam()) + (GetParam() == 0 ? " FSK, SNR in " : " PSK, SNR in ");
  EXPECT_NE(table.out.find(how), std::string::npos) << table.out;
  EXPECT_EQ(table.out.find("snr_in_db="), std::string::npos) << "the driver's text repeats the figures:\n" << table.out;

  // Packet events (one per packet heard) only when asked for: the default
  // listing is the messages' own stories.
  auto kinds_listed = [&](std::vector<std::string> args, const std::string& name) {
    std::vector<std::string> all = {"--socket", net_->socket(1), "events", "--json"};
    all.insert(all.end(), args.begin(), args.end());
    RunResult listed = run(ACOMMSCTL_BINARY, all, (net_->dir() / name).string());
    EXPECT_EQ(listed.exit_code, 0) << listed.err;
    v1::EventsResponse log;
    EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(listed.out, &log).ok()) << listed.out;
    std::multiset<std::string> kinds;
    for (const auto& event : log.events()) kinds.insert(event.kind());
    return kinds;
  };
  const auto by_default = kinds_listed({}, "events-default");
  EXPECT_EQ(by_default.count("packet"), 0u);
  EXPECT_EQ(by_default.count("received"), 1u);
  EXPECT_GE(kinds_listed({"--kind", "packet"}, "events-packet").count("packet"), 1u);
}

INSTANTIATE_TEST_SUITE_P(Rates, MicroModemTwoNode, ::testing::Values(0, 5),
                         [](const ::testing::TestParamInfo<int>& info) { return "Rate" + std::to_string(info.param); });

// driver.micromodem.fdp_data: the same Command as one MM2 FDP packet, and
// the receiving daemon's software ACK (an FDP packet too) clears the
// topside's queue; no $CCCYC goes out.
TEST(MicroModemFdpData, ACommandGoesAsFdpAndTheSoftwareAckClearsTheQueue) {
  MicroModemNetwork net("mm-fdp-data", {{1, "1,mm2,300,0,0"}, {2, "2,mm2,0,0,0"}}, kTimeScale);
  ASSERT_TRUE(net.ok()) << net.fake_output();
  std::string mac = "name: \"fixed\" slot { src: 1 rate: 5 seconds: 4 } slot { src: 2 rate: 5 seconds: 4 }";
  for (int id : {1, 2}) net.write_config(id, mac, "cfg: \"psk.packet.mod_hdr_version,1\" fdp_data: true");
  for (int id : {1, 2}) ASSERT_TRUE(net.start(id)) << net.daemon_log(id);
  StreamSubscriber vehicle(net.socket(1), "example.Command");
  grpc::Status submitted = net.submit_command(2, 1, 7);
  ASSERT_TRUE(submitted.ok()) << submitted.error_message();

  bool heard = vehicle.wait_for([](const auto& received) { return !received.empty(); }, 60s);
  bool cleared = heard && wait_until([&] { return net.queued(2) == 0; }, 30s, 200ms);
  ASSERT_TRUE(heard) << "vehicle:\n" << net.daemon_log(1) << "\ntopside:\n" << net.daemon_log(2);
  EXPECT_EQ(vehicle.received().front().src(), 2);
  EXPECT_TRUE(cleared) << "the software ACK did not clear the topside's queue:\n" << net.daemon_log(2);
  RunResult raw = net.raw_log(2);
  EXPECT_EQ(raw.exit_code, 0) << raw.err;
  EXPECT_NE(raw.out.find(" >> $CCTDP,1,5,0,0,DD01"), std::string::npos) << raw.out.substr(0, 3000);
  EXPECT_EQ(raw.out.find("$CCCYC"), std::string::npos);
  for (int id : {1, 2}) {
    net.daemon(id).signal(SIGTERM);
    EXPECT_EQ(net.daemon(id).wait(15s), std::optional<int>(0)) << "node " << id << ":\n" << net.daemon_log(id);
  }
}

}  // namespace
}  // namespace acomms::testing
