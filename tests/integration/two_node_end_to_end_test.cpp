// The example network end to end: two real acommsd processes (vehicle 1,
// topside 2) on the loopback sim channel with fixed TDMA, driven through the
// gRPC API as the operator and the vehicle's autonomy would.
//
//  1. The topside sends a Command with ACK: the vehicle's subscriber gets it
//     and the ACK clears the topside's queue.
//  2. The vehicle sends a Status every slot: the topside's subscriber gets
//     one in each vehicle slot.
//  3. The vehicle is SIGKILLed holding queued Statuses and restarted: every
//     Status whose Submit returned reaches the topside's subscriber, and it
//     sees none twice (retransmissions are recognised).
#include <gtest/gtest.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "daemon_harness.h"
#include "sim_network.h"
#include "stream_subscriber.h"

namespace acomms::testing {
namespace {

using namespace std::chrono_literals;

constexpr double kSlotSeconds = 3;
constexpr double kCycleSeconds = 2 * kSlotSeconds;

using Subscriber = StreamSubscriber;

// The "seq" field of a received message's JSON.
int seq_of(const v1::ReceivedMessage& message) {
  auto at = message.json().find("\"seq\":");
  return at == std::string::npos ? -1 : std::stoi(message.json().substr(at + 6));
}

class TwoNode : public ::testing::Test {
 protected:
  void SetUp() override {
    for (int id : {1, 2}) {
      net_.write_config(id, {.sim = id == 1 ? "position { x: 300 }" : "position { x: 0 }",
                             .rest = "queue {\n" + SimNetwork::queue_type("example.Status", "max_queue: 1000 ttl_s: 600") +
                                     SimNetwork::queue_type("example.Command", "value_base: 5") + "}\n"});
    }
    net_.start(1);
    net_.start(2);
  }
  void TearDown() override { net_.stop(); }

  int64_t submit(int id, const std::string& type, const std::string& json) {
    grpc::ClientContext context;
    v1::SubmitRequest request;
    request.set_type(type);
    request.set_json(json);
    v1::SubmitResponse response;
    grpc::Status status = api(net_.socket(id))->Submit(&context, request, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return status.ok() ? response.message_id() : -1;
  }

  v1::ListQueuedResponse queued(int id, const std::string& type) {
    grpc::ClientContext context;
    v1::ListQueuedRequest request;
    request.set_type(type);
    v1::ListQueuedResponse response;
    EXPECT_TRUE(api(net_.socket(id))->ListQueued(&context, request, &response).ok());
    return response;
  }

  std::vector<std::string> event_kinds(int id, int64_t message_id) {
    grpc::ClientContext context;
    v1::EventsRequest request;
    request.set_message_id(message_id);
    v1::EventsResponse response;
    EXPECT_TRUE(api(net_.socket(id))->Events(&context, request, &response).ok());
    std::vector<std::string> kinds;
    for (const auto& event : response.events()) kinds.push_back(event.kind());
    return kinds;
  }

  SimNetwork net_{"e2e", kSlotSeconds};
};

TEST_F(TwoNode, CommandStatusAndVehicleCrash) {
  Subscriber topside_status(net_.socket(2), "example.Status");

  // 1. A command with ACK, topside to vehicle.
  {
    Subscriber vehicle_commands(net_.socket(1), "example.Command");
    int64_t id = submit(2, "example.Command", R"({"dest": 1, "kind": "GOTO", "x": 200, "y": -50, "depth": 30, "seq": 7})");
    ASSERT_GT(id, 0);
    ASSERT_TRUE(vehicle_commands.wait_for([](const auto& got) { return !got.empty(); }, 20s))
        << net_.daemon(1).stderr_text();
    const v1::ReceivedMessage command = vehicle_commands.received().front();
    EXPECT_EQ(command.src(), 2);
    EXPECT_EQ(command.dest(), 1);
    EXPECT_EQ(seq_of(command), 7);
    EXPECT_NE(command.json().find("\"kind\":\"GOTO\""), std::string::npos) << command.json();
    EXPECT_EQ(command.link().transmission_src(), 2);
    // The ACK clears the topside's queue, and its event log says so.
    wait_until([&] { return queued(2, "example.Command").messages_size() == 0; }, 10s, 100ms);
    EXPECT_EQ(queued(2, "example.Command").messages_size(), 0);
    std::vector<std::string> history = event_kinds(2, id);
    EXPECT_EQ(history, (std::vector<std::string>{"queued", "sent", "acked"}));
    EXPECT_EQ(vehicle_commands.received().size(), 1u);
  }

  // 2. A status every slot: the vehicle's autonomy queues one a second, and
  // the topside hears one in each of four vehicle slots in a row.
  std::atomic<bool> autonomy_running{true};
  std::atomic<int> next_seq{1};
  std::set<int> confirmed;  // seqs whose Submit returned
  std::mutex confirmed_mutex;
  std::thread autonomy([&] {
    while (autonomy_running) {
      int seq = next_seq++;
      if (submit(1, "example.Status", R"({"dest": 2, "x": 1500, "y": 0, "depth": 30, "seq": )" +
                                         std::to_string(seq) + "}") > 0) {
        std::lock_guard lock(confirmed_mutex);
        confirmed.insert(seq);
      }
      std::this_thread::sleep_for(1s);
    }
  });
  auto cycles_heard = [](const std::vector<v1::ReceivedMessage>& got) {
    std::set<long> cycles;
    for (const auto& m : got) cycles.insert(static_cast<long>(m.receive_time() / kCycleSeconds));
    return cycles;
  };
  bool four_in_a_row = topside_status.wait_for(
      [&](const auto& got) {
        std::set<long> cycles = cycles_heard(got);
        for (long c : cycles) {
          if (cycles.count(c + 1) && cycles.count(c + 2) && cycles.count(c + 3)) return true;
        }
        return false;
      },
      std::chrono::seconds(static_cast<int>(8 * kCycleSeconds)));
  autonomy_running = false;
  autonomy.join();
  EXPECT_TRUE(four_in_a_row) << "statuses heard in " << cycles_heard(topside_status.received()).size()
                             << " cycles\n" << net_.daemon(1).stderr_text();

  // 3. Queue a burst and SIGKILL the vehicle at once: the burst is in its
  // store only. (Statuses ask for an ACK: the queue's default for unicast.)
  for (int i = 0; i < 40; ++i) {
    int seq = next_seq++;
    if (submit(1, "example.Status", R"({"dest": 2, "x": 1500, "y": 0, "depth": 31, "seq": )" +
                                       std::to_string(seq) + "}") > 0) {
      confirmed.insert(seq);
    }
  }
  EXPECT_GT(queued(1, "example.Status").messages_size(), 0);
  net_.daemon(1).signal(SIGKILL);
  ASSERT_TRUE(net_.daemon(1).wait(10s).has_value() || net_.daemon(1).exit_signal() == SIGKILL);
  net_.start(1);

  bool all_delivered = topside_status.wait_for(
      [&](const auto& got) {
        std::set<int> seen;
        for (const auto& m : got) seen.insert(seq_of(m));
        for (int seq : confirmed) {
          if (!seen.count(seq)) return false;
        }
        return true;
      },
      std::chrono::seconds(static_cast<int>(8 * kCycleSeconds)));
  std::map<int, int> times_seen;
  for (const auto& m : topside_status.received()) ++times_seen[seq_of(m)];
  std::vector<int> missing, twice;
  for (int seq : confirmed) {
    if (!times_seen.count(seq)) missing.push_back(seq);
  }
  for (auto [seq, n] : times_seen) {
    if (n > 1) twice.push_back(seq);
  }
  EXPECT_TRUE(all_delivered);
  EXPECT_TRUE(missing.empty()) << missing.size() << " of " << confirmed.size() << " confirmed statuses missing, first "
                               << (missing.empty() ? 0 : missing.front()) << "\n"
                               << net_.daemon(1).stderr_text();
  EXPECT_TRUE(twice.empty()) << twice.size() << " statuses delivered twice, first " << (twice.empty() ? 0 : twice.front());
  // And the ACKs clear the vehicle's queue.
  wait_until([&] { return queued(1, "example.Status").messages_size() == 0; },
             std::chrono::seconds(static_cast<int>(3 * kCycleSeconds)), 200ms);
  v1::ListQueuedResponse left = queued(1, "example.Status");
  EXPECT_EQ(left.messages_size(), 0) << left.DebugString() << net_.daemon(1).stderr_text();
  if (left.messages_size() > 0) {
    for (const auto& k : event_kinds(1, left.messages(0).message_id())) std::cerr << k << " ";
  }
}

}  // namespace
}  // namespace acomms::testing
