// What `acommsctl queue ls` and `queue stats` say on a gateway (config
// `routing`), against a real acommsd (sim driver, alone on its channel, so
// nothing leaves its queues): a message with a route shows where it goes
// next, one with no route says it waits for one (its ttl counting), and
// QueueStats carries the routed counters (delivered, expired_remote).

#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "acomms/v1/acomms.pb.h"
#include "child_process.h"
#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string kAcommsd = ACOMMSD_BINARY;
const std::string kAcommsctl = ACOMMSCTL_BINARY;
const std::string kTestProto = ACOMMS_TEST_PROTO_DIR "/ctl_test.proto";

template <typename Message>
Message parse_json(const std::string& json) {
  Message message;
  auto status = google::protobuf::util::JsonStringToMessage(json, &message);
  EXPECT_TRUE(status.ok()) << status.message() << " in: " << json;
  return message;
}

class AcommsctlGateway : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path("/tmp") / ("acomms-gw-" + std::to_string(::getpid()) + "-" +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    socket_ = (dir_ / "node.sock").string();
    std::ostringstream config;
    // Node 1: vehicles 5-9 through node 2; nothing known of 20 and up.
    config << DaemonConfig{.data_dir = dir_ / "node", .unix_socket = socket_}.text()
           << "driver { name: \"sim\" modem_id: 1 }\n"
           << "mac { name: \"none\" }\n"
           << "dccl { proto_files: \"" << kTestProto << "\" strict: true }\n"
           << "queue { type { type: \"ctltest.VehicleStatus\" roles { source_field: \"header.src\" "
              "destination_field: \"header.dest\" } } }\n"
           << "routing { route { dest_min: 5 dest_max: 9 next_hop: 2 } route { dest: 3 next_hop: 3 } }\n";
    std::ofstream(dir_ / "node.conf") << config.str();
    daemon_ = std::make_unique<ChildProcess>(
        kAcommsd, std::vector<std::string>{"--config", (dir_ / "node.conf").string()}, (dir_ / "acommsd").string());
    ASSERT_TRUE(wait_serving(*daemon_, socket_)) << daemon_->stderr_text();
  }
  void TearDown() override {
    if (daemon_ && daemon_->running()) {
      daemon_->signal(SIGTERM);
      daemon_->wait(10s);
    }
    fs::remove_all(dir_);
  }
  RunResult ctl(std::vector<std::string> args) {
    args.insert(args.begin(), {"--socket", socket_});
    return run(kAcommsctl, args, (dir_ / ("ctl" + std::to_string(++runs_))).string());
  }
  int64_t send_to(int dest) {
    RunResult result = ctl({"send", "ctltest.VehicleStatus", "header.src=1", "header.dest=" + std::to_string(dest),
                            "depth=10"});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return std::atoll(result.out.c_str());
  }
  // The text line of `queue ls` for message `id`.
  std::string ls_line(const std::string& text, int64_t id) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind(std::to_string(id) + " ", 0) == 0) return line;
    }
    return "";
  }

  fs::path dir_;
  std::string socket_;
  std::unique_ptr<ChildProcess> daemon_;
  int runs_ = 0;
};

TEST_F(AcommsctlGateway, QueueLsShowsTheNextHopOfARoutedMessageAndThatOneWithoutARouteWaits) {
  const int64_t relayed = send_to(7);
  const int64_t neighbour = send_to(3);
  const int64_t nowhere = send_to(20);
  ASSERT_GT(relayed, 0);
  ASSERT_GT(nowhere, 0);

  RunResult text = ctl({"queue", "ls"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(ls_line(text.out, relayed).find("(next hop 2 on default) {"), std::string::npos) << text.out;
  EXPECT_NE(ls_line(text.out, neighbour).find("(neighbour, on default) {"), std::string::npos) << text.out;
  EXPECT_NE(ls_line(text.out, nowhere).find("(waits: no route to node 20) {"), std::string::npos) << text.out;

  RunResult json = ctl({"queue", "ls", "--json"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const v1::ListQueuedResponse list = parse_json<v1::ListQueuedResponse>(json.out);
  ASSERT_EQ(list.messages_size(), 3);
  for (const v1::QueuedMessage& m : list.messages()) {
    if (m.message_id() == relayed) {
      EXPECT_EQ(m.next_hop(), 2);
      EXPECT_EQ(m.next_link(), "default");
      EXPECT_EQ(m.waiting(), "");
    } else if (m.message_id() == neighbour) {
      EXPECT_EQ(m.next_hop(), 3);
    } else {
      EXPECT_EQ(m.next_hop(), 0);
      EXPECT_EQ(m.next_link(), "");
      EXPECT_EQ(m.waiting(), "no route to node 20");
      EXPECT_GT(m.expires_at(), 0);  // its ttl counts while it waits
    }
  }
}

// Their values on a working network: system.GatewayFleetTest (the shore's
// and vehicle A's delivered equal their "delivered" events).
TEST_F(AcommsctlGateway, QueueStatsShowsTheRoutedCounters) {
  RunResult text = ctl({"queue", "stats", "ctltest.VehicleStatus"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("DELIVERED"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("EXP-FAR"), std::string::npos) << text.out;
  RunResult json = ctl({"queue", "stats", "--json", "ctltest.VehicleStatus"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find(R"("delivered":"0")"), std::string::npos) << json.out;
  EXPECT_NE(json.out.find(R"("expired_remote":"0")"), std::string::npos) << json.out;
}

}  // namespace
}  // namespace acomms::testing
