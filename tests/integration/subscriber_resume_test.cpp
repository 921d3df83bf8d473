// A topside script that follows received messages with
// `acommsctl sub --resume FILE` misses nothing and sees nothing twice,
// whatever dies: two real acommsd processes (vehicle 1, topside 2) on the
// loopback sim channel, the vehicle sending a Status a second throughout.
//
//  1. The subscriber is SIGKILLed; Statuses keep arriving while it is away;
//     a new one started with the same FILE goes on from its cursor.
//  2. Then the topside daemon itself is SIGKILLed (its subscriber's stream
//     ends), restarted, and a third subscriber goes on from FILE.
// The union of the three subscribers' lines is every message in the
// topside's event log exactly once, in order: seqs 1..N, each once, N the
// number of received events.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include "daemon_harness.h"
#include "queue/event_log_retention.h"
#include "queue/sqlite_journal.h"
#include "sim_network.h"
#include "store/group_commit_writer.h"
#include "store/store.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr double kSlotSeconds = 3;

// An integer field `"name":N` of a JSON line; -1 when absent.
int64_t field_of(const std::string& line, const std::string& name) {
  const std::string key = "\"" + name + "\":";
  // The last occurrence: the line's own "seq" follows the message's.
  auto at = line.rfind(key);
  return at == std::string::npos ? -1 : std::stoll(line.substr(at + key.size()));
}

// The message's own "seq" field (the Status counter), inside "message".
int64_t status_counter_of(const std::string& line) {
  auto message = line.find("\"message\":");
  if (message == std::string::npos) return -1;
  auto at = line.find("\"seq\":", message);
  return at == std::string::npos ? -1 : std::stoll(line.substr(at + 6));
}

class SubscriberResume : public ::testing::Test {
 protected:
  void SetUp() override {
    for (int id : {1, 2}) {
      net_.write_config(id, {.sim = id == 1 ? "position { x: 300 }" : "position { x: 0 }",
                             .rest = "queue {\n" +
                                     SimNetwork::queue_type("example.Status", "max_queue: 1000 ttl_s: 600") + "}\n"});
    }
    net_.start(1);
    net_.start(2);
  }
  void TearDown() override { net_.stop(); }

  std::string cursor_file() const { return (net_.dir() / "sub.cursor").string(); }

  // `acommsctl sub --resume FILE` on the topside, connected when this returns.
  std::unique_ptr<ChildProcess> start_subscriber(int n) {
    std::set<uint64_t> before = unix_connections(net_.socket(2));
    auto sub = std::make_unique<ChildProcess>(
        ACOMMSCTL_BINARY,
        std::vector<std::string>{"--socket", net_.socket(2), "sub", "example.Status", "--resume", cursor_file()},
        (net_.dir() / ("sub" + std::to_string(n))).string());
    EXPECT_TRUE(wait_connected(*sub, net_.socket(2), before)) << sub->stderr_text();
    return sub;
  }

  int64_t cursor() const {
    std::ifstream in(cursor_file());
    int64_t seq = -1;
    in >> seq;
    return seq;
  }

  // Received events in the topside's event log.
  int received_events() {
    grpc::ClientContext context;
    v1::EventsRequest request;
    request.add_kinds("received");
    request.set_limit(10000);
    v1::EventsResponse response;
    grpc::Status status = api(net_.socket(2))->Events(&context, request, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return response.events_size();
  }

  int queued_on_vehicle() {
    grpc::ClientContext context;
    v1::ListQueuedRequest request;
    request.set_type("example.Status");
    v1::ListQueuedResponse response;
    EXPECT_TRUE(api(net_.socket(1))->ListQueued(&context, request, &response).ok());
    return response.messages_size();
  }

  SimNetwork net_{"resume", kSlotSeconds};
};

TEST_F(SubscriberResume, KilledSubscriberThenKilledDaemonMissNothingAndRepeatNothing) {
  std::atomic<bool> autonomy_running{true};
  std::thread autonomy([&] {
    for (int counter = 1; autonomy_running; ++counter) {
      grpc::ClientContext context;
      v1::SubmitRequest request;
      request.set_type("example.Status");
      request.set_json(R"({"dest": 2, "x": 1500, "y": 0, "depth": 30, "seq": )" + std::to_string(counter) + "}");
      v1::SubmitResponse response;
      (void)api(net_.socket(1))->Submit(&context, request, &response);
      std::this_thread::sleep_for(1s);
    }
  });
  auto lines = [](ChildProcess& sub) { return lines_of(sub.stdout_text()); };
  const auto kWait = std::chrono::milliseconds(static_cast<int>(12 * kSlotSeconds * 1000));
  std::vector<std::string> printed;

  // 1. The first subscriber prints a few, and is killed between messages
  //    (its cursor file holds its last line's seq: nothing is half done).
  auto first = start_subscriber(1);
  ASSERT_TRUE(wait_until(
      [&] {
        auto got = lines(*first);
        return got.size() >= 2 && cursor() == field_of(got.back(), "seq");
      },
      kWait))
      << first->stderr_text();
  first->signal(SIGKILL);
  first->wait(10s);
  for (const std::string& line : lines(*first)) printed.push_back(line);
  const int64_t first_last = field_of(printed.back(), "seq");
  // Messages keep arriving while nobody listens.
  ASSERT_TRUE(wait_until([&] { return received_events() >= first_last + 3; }, kWait));

  // 2. The second goes on from the cursor; then the topside dies under it.
  auto second = start_subscriber(2);
  ASSERT_TRUE(wait_until([&] { return lines(*second).size() >= 4; }, kWait)) << second->stderr_text();
  net_.daemon(2).signal(SIGKILL);
  net_.daemon(2).wait(10s);
  EXPECT_TRUE(second->wait(20s).has_value()) << "the subscriber outlived its daemon's stream";
  for (const std::string& line : lines(*second)) printed.push_back(line);
  net_.start(2);

  // 3. The third goes on from the cursor, past the restart.
  auto third = start_subscriber(3);
  const int64_t before_third = field_of(printed.back(), "seq");
  ASSERT_TRUE(wait_until(
      [&] {
        auto got = lines(*third);
        return got.size() >= 4 && field_of(got.back(), "seq") > before_third + 3;
      },
      kWait))
      << third->stderr_text() << net_.daemon(2).stderr_text();
  autonomy_running = false;
  autonomy.join();
  // Once the vehicle's queue is empty nothing more arrives: the count is final.
  ASSERT_TRUE(wait_until([&] { return queued_on_vehicle() == 0; }, kWait));
  const int total = received_events();
  ASSERT_TRUE(wait_until([&] { return !lines(*third).empty() && field_of(lines(*third).back(), "seq") >= total; },
                         kWait));
  third->signal(SIGTERM);
  EXPECT_EQ(third->wait(10s), std::optional<int>(0)) << third->stderr_text();
  for (const std::string& line : lines(*third)) printed.push_back(line);

  // The union: seqs 1..total, each exactly once, in order; and no Status
  // (by its own counter) twice.
  ASSERT_EQ(printed.size(), static_cast<size_t>(total));
  std::set<int64_t> counters;
  for (size_t i = 0; i < printed.size(); ++i) {
    EXPECT_EQ(field_of(printed[i], "seq"), static_cast<int64_t>(i + 1)) << printed[i];
    EXPECT_TRUE(counters.insert(status_counter_of(printed[i])).second) << "printed twice: " << printed[i];
  }
  EXPECT_GT(first_last, 0);
}

// A replay that asks for pruned history is refused, naming the first seq
// still held; one that starts at or after it is served. The store is
// prepared and pruned (one real pruning step) before acommsd opens it.
TEST(SubscribeReplay, PrunedHistoryIsOutOfRangeNamingTheFirstSeqStillHeld) {
  const fs::path dir = fs::path("/tmp") / ("acomms-replay-range-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const double now = static_cast<double>(std::time(nullptr));
  {
    store::Store store((dir / "data").string());
    store::GroupCommitWriter writer(store.db());
    queue::SqliteJournal journal(writer);
    for (int64_t seq = 1; seq <= 6; ++seq) {
      queue::QueueEvent e;
      e.kind = queue::QueueEventKind::kReceived;
      e.time = seq <= 5 ? now - 100 * 86400.0 : now;  // 1..5 long past the bound
      e.type = "example.Status";
      e.src = 2;
      e.dest = 1;
      e.encoded = "not dccl";
      e.seq = seq;
      journal.record(e);
    }
    queue::RetentionPolicy policy;
    policy.max_age_s = 90 * 86400.0;
    policy.max_bytes = 0;
    size_t pruned = writer
                        .submit([&](store::Database& db) {
                          return queue::prune_event_log_step(db, policy, now, now - 300);
                        })
                        .get();
    ASSERT_EQ(pruned, 5u);
  }
  const std::string socket = (dir / "d.sock").string();
  {
    std::ofstream config(dir / "d.conf");
    config << DaemonConfig{.data_dir = dir / "data",
                           .unix_socket = socket,
                           .proto_file = ACOMMS_SOURCE_DIR "/examples/messages.proto"}.text()
           << "driver { name: \"sim\" modem_id: 1 sim { listen: \"127.0.0.1:" << free_udp_port() << "\" } }\n";
  }
  ChildProcess daemon(ACOMMSD_BINARY, {"--config", (dir / "d.conf").string()}, (dir / "d").string());
  ASSERT_TRUE(wait_serving(daemon, socket)) << daemon.stderr_text();
  auto stub = api(socket);
  {
    grpc::ClientContext context;
    v1::SubscribeRequest request;
    request.set_after(2);
    auto reader = stub->Subscribe(&context, request);
    v1::ReceivedMessage message;
    EXPECT_FALSE(reader->Read(&message));
    grpc::Status status = reader->Finish();
    EXPECT_EQ(status.error_code(), grpc::StatusCode::OUT_OF_RANGE);
    EXPECT_NE(status.error_message().find("first still held is 6"), std::string::npos) << status.error_message();
  }
  {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + 10s);
    v1::SubscribeRequest request;
    request.set_after(5);  // had everything up to the pruned part
    auto reader = stub->Subscribe(&context, request);
    v1::ReceivedMessage message;
    ASSERT_TRUE(reader->Read(&message));
    EXPECT_EQ(message.seq(), 6);
    EXPECT_EQ(message.type(), "example.Status");
    context.TryCancel();
    reader->Finish();
  }
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.wait(15s), std::optional<int>(0)) << daemon.stderr_text();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace acomms::testing
