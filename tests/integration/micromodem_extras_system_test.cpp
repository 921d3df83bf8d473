// The Micro-Modem's own transmissions between two real acommsd processes,
// each on its own fake Micro-Modem (one fake_micromodem process: two MM2
// modems 1500 m apart plus LBL transponders, on TCP ports), fixed TDMA,
// through acommsctl: `link ping` gives the travel time of the fake's
// geometry, `link lbl` both kinds with a transponder that never answers,
// and `link mini` reaches the other daemon's subscriber as its own message
// type. The fake and drivers run 4x faster than real time; the MAC's slots
// are real seconds, so each request first waits for its node's slot: the
// raw link logs show each extra's first command at its node's slot start.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <thread>

#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr double kTimeScale = 4;

class MicroModemExtras : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path("/tmp") / ("acomms-mmx-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // Modem 1 at the origin, modem 2 1500 m east (1.0 s). Narrowband
    // transponders: 26 kHz 750 m north (0.5 s), 28 kHz silent; REMUS A
    // 300 m down (0.2 s), B silent.
    fake_ = std::make_unique<ChildProcess>(
        FAKE_MICROMODEM_BINARY,
        std::vector<std::string>{"--transport", "tcp", "--modem", "1,mm2,0,0,0", "--modem", "2,mm2,1500,0,0",
                                 "--transponder", "nb,26000,0,750,0", "--transponder", "nb,28000,0,100,0,silent",
                                 "--transponder", "remus,A,0,0,300", "--transponder", "remus,B,0,200,0,silent",
                                 "--time-scale", std::to_string(kTimeScale)},
        (dir_ / "fake").string());
    ASSERT_TRUE(wait_until([this] { return ports_known(); }, 10s)) << fake_->stdout_text() << fake_->stderr_text();
    for (int id : {1, 2}) write_config(id);
    for (int id : {1, 2}) start(id);
  }
  void TearDown() override {
    for (auto& [id, daemon] : daemons_) {
      if (!daemon || !daemon->running()) continue;
      daemon->signal(SIGTERM);
      EXPECT_EQ(daemon->wait(15s), std::optional<int>(0)) << id << ":\n" << daemon->stderr_text();
    }
    if (fake_) fake_->signal(SIGTERM);
    fs::remove_all(dir_);
  }

  bool ports_known() {
    for (const std::string& line : lines_of(fake_->stdout_text())) {
      int id = 0;
      char address[64] = {};
      if (std::sscanf(line.c_str(), "modem %d mm2 tcp %63s", &id, address) == 2) address_[id] = address;
    }
    return address_.size() == 2;
  }
  std::string socket(int id) const { return (dir_ / ("node" + std::to_string(id) + ".sock")).string(); }

  void write_config(int id) {
    std::ofstream config(dir_ / ("node" + std::to_string(id) + ".conf"));
    config << DaemonConfig{.data_dir = dir_ / ("node" + std::to_string(id)),
                           .unix_socket = socket(id),
                           .proto_file = ACOMMS_SOURCE_DIR "/examples/messages.proto"}.text()
           << "driver { name: \"micromodem\" modem_id: " << id << " micromodem { port: \"tcp:" << address_[id]
           << "\" time_scale: " << kTimeScale << " max_range_m: 2000 } }\n"
           << "mac { " << mac_for(id) << " }\n";
  }
  // Fixed TDMA: node 1 in [0, 3) s, node 2 in [3, 6) s of each 6 s cycle.
  virtual std::string mac_for(int) const {
    return "name: \"fixed\" slot { src: 1 rate: 1 seconds: 3 } slot { src: 2 rate: 1 seconds: 3 }";
  }
  void start(int id) {
    daemons_[id] = std::make_unique<ChildProcess>(
        ACOMMSD_BINARY, std::vector<std::string>{"--config", (dir_ / ("node" + std::to_string(id) + ".conf")).string()},
        (dir_ / ("node" + std::to_string(id))).string() + "-log");
    ASSERT_TRUE(wait_serving(*daemons_[id], socket(id))) << daemons_[id]->stderr_text();
  }
  RunResult ctl(int id, std::vector<std::string> args) {
    args.insert(args.begin(), {"--socket", socket(id)});
    return run(ACOMMSCTL_BINARY, args, (dir_ / ("ctl" + std::to_string(++runs_))).string());
  }
  // Seconds into the 6 s TDMA cycle (slots align to midnight UTC) at which
  // node `id` wrote the first line starting with `prefix`; -1 if none.
  double cycle_offset_of(int id, const std::string& prefix) {
    std::ifstream raw(dir_ / ("node" + std::to_string(id)) / "link-raw.log");
    std::string line;
    while (std::getline(raw, line)) {
      size_t at = line.find(" >> ");
      if (at == std::string::npos || line.compare(at + 4, prefix.size(), prefix) != 0) continue;
      int hour = 0, minute = 0;
      double second = 0;
      if (std::sscanf(line.c_str(), "%*d-%*d-%*dT%d:%d:%lfZ", &hour, &minute, &second) != 3) return -1;
      return std::fmod(hour * 3600.0 + minute * 60.0 + second, 6.0);
    }
    return -1;
  }
  std::string logs() { return "node 1:\n" + daemons_[1]->stderr_text() + "\nnode 2:\n" + daemons_[2]->stderr_text(); }

  fs::path dir_;
  std::unique_ptr<ChildProcess> fake_;
  std::map<int, std::string> address_;
  std::map<int, std::unique_ptr<ChildProcess>> daemons_;
  int runs_ = 0;
};

TEST_F(MicroModemExtras, PingLblAndAMiniPacketThroughAcommsctl) {
  // The modems come up while the first slots pass: each request waits for
  // its node's slot, and the drivers must be ready by then.
  ASSERT_TRUE(wait_until([&] { return ctl(2, {"link", "status"}).out.find("running") != std::string::npos; }, 20s));

  // Ping: within 2 ms of 1500 m / 1500 m/s.
  RunResult ping;
  for (int tries = 0; tries < 3; ++tries) {  // the first may come before the modem's start-up ended
    ping = ctl(2, {"link", "ping", "1", "--wait", "30"});
    if (ping.exit_code == 0) break;
  }
  ASSERT_EQ(ping.exit_code, 0) << ping.err << logs();
  double travel = 0, range = 0, waited = -1;
  ASSERT_EQ(std::sscanf(ping.out.c_str(), "modem 1: one-way travel time %lf s, range %lf m (waited %lf s", &travel,
                        &range, &waited),
            3)
      << ping.out;
  EXPECT_NEAR(travel, 1.0, 0.002) << ping.out;
  EXPECT_NEAR(range, 1500, 3);
  EXPECT_GT(waited, 0);  // a request never goes before its node's next slot begins
  // The slot rule on the wire: node 2's slot is [3, 6) s of each cycle, and
  // the ping's command left at its start.
  double ping_at = cycle_offset_of(2, "$CCMPC,2,1*");
  EXPECT_GE(ping_at, 3.0);
  EXPECT_LT(ping_at, 3.5);

  // Narrowband LBL from node 1: A answers (0.5 s), the 28 kHz one does not.
  RunResult nb = ctl(1, {"link", "lbl", "--narrowband", "26000,28000", "--wait", "30"});
  ASSERT_EQ(nb.exit_code, 0) << nb.err << logs();
  EXPECT_NE(nb.out.find("A (26000 Hz) one-way travel time 0.5000 s, range 750.0 m"), std::string::npos) << nb.out;
  EXPECT_NE(nb.out.find("B (28000 Hz) no reply"), std::string::npos) << nb.out;
  double lbl_at = cycle_offset_of(1, "$CCCFG,TAT,50*");  // the LBL's first command, in node 1's slot [0, 3)
  EXPECT_GE(lbl_at, 0.0);
  EXPECT_LT(lbl_at, 0.5);

  // REMUS LBL: A at 300 m (0.2 s), B silent.
  RunResult remus = ctl(1, {"link", "lbl", "--remus", "AB", "--wait", "30"});
  ASSERT_EQ(remus.exit_code, 0) << remus.err << logs();
  EXPECT_NE(remus.out.find("A            one-way travel time 0.2000 s, range 300.0 m"), std::string::npos)
      << remus.out;
  EXPECT_NE(remus.out.find("B            no reply"), std::string::npos) << remus.out;

  // A mini-packet from node 2 reaches node 1's subscriber as its own type.
  auto stub = api(socket(1));
  grpc::ClientContext subscribe_context;
  v1::SubscribeRequest subscribe;
  subscribe.add_types("acomms.drivers.MicroModemMiniPacket");
  auto reader = stub->Subscribe(&subscribe_context, subscribe);
  reader->WaitForInitialMetadata();
  std::mutex mutex;
  std::vector<v1::ReceivedMessage> received;
  std::thread reading([&] {
    v1::ReceivedMessage message;
    while (reader->Read(&message)) {
      std::lock_guard lock(mutex);
      received.push_back(message);
    }
  });
  RunResult mini = ctl(2, {"link", "mini", "1", "0x1ABC", "--wait", "30"});
  bool heard = mini.exit_code == 0 && wait_until(
                                          [&] {
                                            std::lock_guard lock(mutex);
                                            return !received.empty();
                                          },
                                          10s, 50ms);
  subscribe_context.TryCancel();
  reading.join();
  ASSERT_EQ(mini.exit_code, 0) << mini.err << logs();
  ASSERT_TRUE(heard) << logs();
  EXPECT_EQ(received[0].type(), "acomms.drivers.MicroModemMiniPacket");
  EXPECT_EQ(received[0].src(), 2);
  EXPECT_EQ(received[0].dest(), 1);
  EXPECT_NE(received[0].json().find("\"value\":6844"), std::string::npos) << received[0].json();
}

// Node 1 is the polled master; node 2 (MAC "none") has no slot of its own:
// its ping goes when the master's poll gives it the channel, after the
// poll's answer (one blank frame).
class MicroModemExtrasPolled : public MicroModemExtras {
 protected:
  std::string mac_for(int id) const override {
    return id == 1 ? "name: \"polled\" slot { src: 1 rate: 1 seconds: 3 } slot { src: 2 dest: 1 rate: 1 seconds: 3 }"
                   : "name: \"none\"";
  }
  // Outgoing lines of node `id`'s raw log, in order.
  std::vector<std::string> written(int id) {
    std::ifstream raw(dir_ / ("node" + std::to_string(id)) / "link-raw.log");
    std::vector<std::string> out;
    for (std::string line; std::getline(raw, line);) {
      size_t at = line.find(" >> ");
      if (at != std::string::npos) out.push_back(line.substr(at + 4));
    }
    return out;
  }
};

TEST_F(MicroModemExtrasPolled, ANodeWithoutSlotsPingsWhenAPollGivesItTheChannel) {
  ASSERT_TRUE(wait_until([&] { return ctl(2, {"link", "status"}).out.find("running") != std::string::npos; }, 20s));
  RunResult ping;
  for (int tries = 0; tries < 3; ++tries) {
    ping = ctl(2, {"link", "ping", "1", "--wait", "30"});
    if (ping.exit_code == 0) break;
  }
  ASSERT_EQ(ping.exit_code, 0) << ping.err << logs();
  double travel = 0, range = 0, waited = -1;
  ASSERT_EQ(std::sscanf(ping.out.c_str(), "modem 1: one-way travel time %lf s, range %lf m (waited %lf s", &travel,
                        &range, &waited),
            3)
      << ping.out;
  EXPECT_NEAR(travel, 1.0, 0.002);
  EXPECT_GT(waited, 0);
  // Node 2's last command before the ping answered the poll ($CCTXD, the
  // blank frame); keep-alive queries aside.
  std::vector<std::string> lines = written(2);
  auto ping_line = std::find_if(lines.begin(), lines.end(), [](const std::string& l) { return l.starts_with("$CCMPC,2,1*"); });
  ASSERT_NE(ping_line, lines.end());
  std::string before;
  for (auto it = lines.begin(); it != ping_line; ++it) {
    if (!it->starts_with("$CCCFQ")) before = *it;
  }
  EXPECT_TRUE(before.starts_with("$CCTXD,2,")) << "before the ping: " << before;
}

}  // namespace
}  // namespace acomms::testing
