// The link's loss counters end to end: what a driver counts reaches
// LinkStatus and `acommsctl link status` (issue 13: a link that delivered
// nothing for minutes, and no counter said why).
//
// Two real acommsd processes on the loopback sim channel.

#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>

#include "acomms/v1/acomms.pb.h"
#include "child_process.h"
#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string kAcommsd = ACOMMSD_BINARY;
const std::string kAcommsctl = ACOMMSCTL_BINARY;

template <typename Message>
Message parse_json(const std::string& json) {
  Message message;
  auto status = google::protobuf::util::JsonStringToMessage(json, &message);
  EXPECT_TRUE(status.ok()) << status.message() << " in: " << json;
  return message;
}

// Nodes on one loopback sim channel, all at the origin, each with its own
// cycle of 2 s slots at rate 5 (max_range_m 0: no travel to guard).
class Network {
 public:
  Network(const std::string& tag, const std::map<int, std::pair<int, int>>& cycles)
      : dir_(fs::path("/tmp") / ("acomms-lc-" + tag + "-" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::map<int, int> port;
    for (const auto& [id, cycle] : cycles) port[id] = free_udp_port();
    for (const auto& [id, cycle] : cycles) {
      std::string name = "n" + std::to_string(id);
      std::ofstream config(dir_ / (name + ".conf"));
      config << DaemonConfig{.data_dir = dir_ / name, .unix_socket = socket(id)}.text()
             << "driver { name: \"sim\" modem_id: " << id << " sim { listen: \"127.0.0.1:" << port[id] << "\"";
      for (const auto& [other, unused] : cycles) {
        if (other != id) config << " peers: \"127.0.0.1:" << port[other] << "\"";
      }
      config << " } }\n"
             << "mac { name: \"fixed\" max_range_m: 0 slot { src: " << cycle.first
             << " rate: 5 seconds: 2 } slot { src: " << cycle.second << " rate: 5 seconds: 2 } }\n";
      config.close();
      nodes_[id] = std::make_unique<ChildProcess>(kAcommsd, std::vector<std::string>{"--config", (dir_ / (name + ".conf")).string()},
                                                  (dir_ / name).string());
    }
    for (auto& [id, node] : nodes_) EXPECT_TRUE(wait_serving(*node, socket(id))) << node->stderr_text();
  }
  ~Network() {
    for (auto& [id, node] : nodes_) node->signal(SIGTERM);
    for (auto& [id, node] : nodes_) node->wait(10s);
    fs::remove_all(dir_);
  }

  std::string socket(int id) const { return (dir_ / ("n" + std::to_string(id) + ".sock")).string(); }
  ChildProcess& node(int id) { return *nodes_.at(id); }
  RunResult ctl(int id, std::vector<std::string> args) {
    args.insert(args.begin(), {"--socket", socket(id)});
    return run(kAcommsctl, args, (dir_ / "ctl").string());
  }
  // Waits (up to 30 s) until `done` holds for node id's LinkStatus; returns the last.
  v1::LinkStatusResponse status_when(int id, const std::function<bool(const v1::LinkCounters&)>& done) {
    v1::LinkStatusResponse link;
    wait_until(
        [&] {
          RunResult status = ctl(id, {"link", "status", "--json"});
          if (status.exit_code != 0) return false;
          link = parse_json<v1::LinkStatusResponse>(status.out);
          return done(link.counters());
        },
        30s, 500ms);
    return link;
  }

 private:
  fs::path dir_;
  std::map<int, std::unique_ptr<ChildProcess>> nodes_;
};

// Two nodes whose cycles disagree (each thinks the first slot is its own)
// transmit at the same moments: each hears the other's packet while
// transmitting and loses it.
TEST(LinkCounters, LinkStatusCountsPacketsLostToHalfDuplex) {
  Network net("hd", {{1, {1, 2}}, {2, {2, 1}}});
  v1::LinkStatusResponse link =
      net.status_when(2, [](const v1::LinkCounters& c) { return c.lost_half_duplex() >= 2; });
  EXPECT_GE(link.counters().lost_half_duplex(), 2u) << link.DebugString() << net.node(2).stderr_text();
  EXPECT_EQ(link.counters().lost_collision(), 0u);
  EXPECT_EQ(link.counters().data_received(), 0u);
  // Logged once for the burst, not once per packet.
  const std::string log = net.node(2).stderr_text();
  const std::string first = "packet from 1 lost to half-duplex";
  EXPECT_NE(log.find(first), std::string::npos) << log;
  EXPECT_EQ(log.find(first, log.find(first) + 1), std::string::npos) << log;

  RunResult human = net.ctl(2, {"link", "status"});
  EXPECT_EQ(human.exit_code, 0) << human.err;
  EXPECT_NE(human.out.find("lost to half-duplex "), std::string::npos) << human.out;
  EXPECT_NE(human.out.find(", lost to collisions 0"), std::string::npos) << human.out;
}

// Nodes 1 and 3 both send in the first slot; node 2 listens then, and their
// packets overlap at it.
TEST(LinkCounters, LinkStatusCountsPacketsLostToCollisions) {
  Network net("col", {{1, {1, 2}}, {2, {1, 2}}, {3, {3, 2}}});
  v1::LinkStatusResponse link =
      net.status_when(2, [](const v1::LinkCounters& c) { return c.lost_collision() >= 4; });
  EXPECT_GE(link.counters().lost_collision(), 4u) << link.DebugString() << net.node(2).stderr_text();
  EXPECT_EQ(link.counters().lost_half_duplex(), 0u);
  EXPECT_EQ(link.counters().data_received(), 0u);
  const std::string log = net.node(2).stderr_text();
  const std::string first = "lost in a collision";
  EXPECT_NE(log.find(first), std::string::npos) << log;
  EXPECT_EQ(log.find(first, log.find(first) + 1), std::string::npos) << log;
  RunResult human = net.ctl(2, {"link", "status"});
  EXPECT_NE(human.out.find("lost to half-duplex 0, lost to collisions "), std::string::npos) << human.out;
}

}  // namespace
}  // namespace acomms::testing
