// Issue 30's "must be shown, in CI": a shore, a gateway buoy (Iridium to the
// shore on the fakes, acoustic to the vehicles) and two vehicles, vehicle B
// reachable only through vehicle A, all real acommsd processes
// (gateway_fleet.h draws the network and says why it is built so).
//
// Shown in one run, because each start of the network costs seconds of
// real time: Commands from the shore reach each vehicle once and Statuses
// from both vehicles reach the shore once, while the buoy is SIGKILLed at
// random moments when it holds messages and restarted on its data dir; each
// origin hears one hop ack and one end-to-end ack per message; a
// SurveyPlan, a type the buoy never loaded, reaches B with the shore's DCCL
// bytes; a Command for node 20, which the buoy and A route to each other,
// ends at the hop limit. The routes the buoy and the shore learned are
// checked, and the network's figures (messages, hops, acks, delay per hop,
// wall time) are printed.
//
// Counting is by content: every message carries a number of its own (seq,
// or plan), and every subscriber's stream is kept whole; the vehicles and
// the shore are never killed, so their streams miss nothing.
//
// ACOMMS_GATEWAY_FLEET_KILLS sets how many times the buoy dies (default 4).

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <map>
#include <mutex>
#include <random>
#include <regex>
#include <thread>

#include "daemon_harness.h"
#include "gateway_fleet.h"
#include "hop_trace.h"
#include "stream_subscriber.h"

namespace acomms::testing {
namespace {

using namespace std::chrono_literals;

constexpr int kPlan = 777;
constexpr int kLoopCommand = 999;
constexpr auto kStatusPeriod = std::chrono::milliseconds(4000);  // per vehicle
// How long vehicle A may hold a message it relays: its transmissions take
// turns between its two next hops (a message waits up to 2 cycles for its
// neighbour's turn), a full frame puts the rest off by one more turn (2
// cycles), and the end-to-end acks of both directions share A's slots with
// the messages; so 5 cycles of 3 slots. The head-of-line wait this guards
// against (a held message blocking those behind it for the other next hop)
// measured 24 to 94 s; the deterministic tests of it are the simulated
// system.GatewayNetwork.*HoldBack* cases.
constexpr double kRelayWaitBoundS = 5 * 3 * kAcousticSlotS;

int kills_wanted() {
  const char* text = std::getenv("ACOMMS_GATEWAY_FLEET_KILLS");
  return text ? std::max(1, std::atoi(text)) : 4;
}

// The message's own number: "seq" (Command, Status) or "plan" (SurveyPlan).
int number_of(const v1::ReceivedMessage& m) {
  static const std::regex number(R"re("(seq|plan)":\s*(\d+))re");
  std::smatch match;
  const std::string json = m.json();
  return std::regex_search(json, match, number) ? std::stoi(match[2]) : -1;
}

v1::ListRoutesResponse routes(const std::string& socket) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + 5s);
  v1::ListRoutesResponse response;
  if (!api(socket)->ListRoutes(&context, {}, &response).ok()) response.set_custody_held(~0ull);  // not answering
  return response;
}

bool has_route(const v1::ListRoutesResponse& r, int dest, int next_hop, const std::string& link,
               const std::string& source) {
  for (const v1::Route& route : r.routes()) {
    if (route.dest_min() <= dest && dest <= route.dest_max() && route.next_hop() == next_hop &&
        route.link() == link && route.source() == source && !route.stale()) {
      return true;
    }
  }
  return false;
}

std::string describe(const v1::ListRoutesResponse& r) {
  std::string out;
  for (const v1::Route& route : r.routes()) {
    out += "    " + std::to_string(route.dest_min()) + "-" + std::to_string(route.dest_max()) + " via " +
           std::to_string(route.next_hop()) + " on " + route.link() + " (" + route.source() + ")\n";
  }
  return out + "    custody held " + std::to_string(r.custody_held()) + ", taken " +
         std::to_string(r.custody_taken()) + ", copies " + std::to_string(r.custody_copies()) + "; delivered " +
         std::to_string(r.delivered()) + ", duplicates " + std::to_string(r.duplicates()) + ", hop limit " +
         std::to_string(r.hop_limit_dropped()) + "\n";
}

// The DCCL bytes of a message given as JSON or as serialized protobuf.
std::string encode(const std::string& socket, const std::string& type, const std::string& json,
                   const std::string& payload) {
  grpc::ClientContext context;
  v1::EncodeRequest request;
  request.set_type(type);
  if (json.empty()) {
    request.set_payload(payload);
  } else {
    request.set_json(json);
  }
  v1::EncodeResponse response;
  grpc::Status status = api(socket)->Encode(&context, request, &response);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return response.encoded();
}

bool loads_type(const std::string& socket, const std::string& type) {
  grpc::ClientContext context;
  v1::ListTypesResponse response;
  EXPECT_TRUE(api(socket)->ListTypes(&context, {}, &response).ok());
  for (const v1::TypeInfo& t : response.types()) {
    if (t.name() == type) return true;
  }
  return false;
}

// What a message's origin logged about its acknowledgements
// (message_history): the hop ack ("acked": the first hop has it) and the
// end-to-end ack ("delivered": the destination's receipt came back along
// the reverse route), each once.
struct OriginAcks {
  int hop_acks = 0;
  int end_to_end_acks = 0;
  std::map<std::string, int> kinds;
};
OriginAcks origin_acks(const std::string& socket, int64_t message_id) {
  OriginAcks acks;
  for (const v1::Event& e : message_history(socket, message_id)) {
    ++acks.kinds[e.kind()];
    acks.hop_acks += e.kind() == "acked";
    acks.end_to_end_acks += e.kind() == "delivered";
  }
  return acks;
}

class GatewayFleetTest : public ::testing::Test {
 protected:
  // Submits at `node`; the message's id there, or 0 (a failure recorded).
  int64_t submit(int node, const std::string& type, const std::string& json) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + 10s);
    v1::SubmitRequest request;
    request.set_type(type);
    request.set_json(json);
    v1::SubmitResponse response;
    grpc::Status status = api(fleet_.socket(node))->Submit(&context, request, &response);
    EXPECT_TRUE(status.ok()) << GatewayFleet::name(node) << " refused " << json << ": " << status.error_message();
    return status.ok() ? response.message_id() : 0;
  }
  // The nodes a message passes, origin first (the loop's: its origin only).
  static std::vector<int> path_of(int origin, int dest) {
    if (origin == kShore && dest == kVehicleA) return {kShore, kBuoy, kVehicleA};
    if (origin == kShore && dest == kVehicleB) return {kShore, kBuoy, kVehicleA, kVehicleB};
    if (origin == kVehicleA && dest == kShore) return {kVehicleA, kBuoy, kShore};
    if (origin == kVehicleB && dest == kShore) return {kVehicleB, kVehicleA, kBuoy, kShore};
    return {origin};
  }
  // A message from `origin` to `dest` numbered `number` (its `fields`
  // besides src, dest and time), traced; returns its JSON.
  std::string send(int origin, int dest, const std::string& type, int number, const std::string& fields) {
    const std::string json = R"({"src": )" + std::to_string(origin) + R"(, "dest": )" + std::to_string(dest) +
                             R"(, "time": )" + std::to_string(std::time(nullptr)) + ", " + fields + "}";
    const int64_t id = submit(origin, type, json);
    std::lock_guard lock(mutex_);
    sent_[number] = {type, origin, dest, id, path_of(origin, dest), 0};
    return json;
  }
  void command(int dest, int seq) {
    send(kShore, dest, "example.Command", seq, R"("kind": "HOLD", "x": 10, "y": 20, "seq": )" + std::to_string(seq));
  }
  void status(int vehicle, int seq) {
    send(vehicle, kShore, "example.Status", seq,
         R"("x": 100, "y": -50, "depth": 12.5, "battery": 80, "seq": )" + std::to_string(seq));
  }

  // number -> copies delivered to the right node (a copy at a wrong node
  // is a failure of its own).
  std::map<int, int> deliveries() {
    std::map<int, int> copies;
    auto count = [&](StreamSubscriber& s, int node) {
      for (const v1::ReceivedMessage& m : s.received()) {
        const int n = number_of(m);
        std::lock_guard lock(mutex_);
        auto it = sent_.find(n);
        if (it == sent_.end() || it->second.destination != node || m.src() != it->second.origin) {
          wrong_.push_back(GatewayFleet::name(node) + " got " + m.type() + " " + m.json() + " from " +
                           std::to_string(m.src()));
          continue;
        }
        ++copies[n];
        if (it->second.delivered_at == 0) it->second.delivered_at = m.receive_time();
      }
    };
    wrong_.clear();
    count(*shore_statuses_, kShore);
    count(*a_commands_, kVehicleA);
    count(*b_commands_, kVehicleB);
    count(*b_plans_, kVehicleB);
    return copies;
  }
  // The numbers sent to `dest` (0: every destination) not yet delivered.
  std::vector<int> missing(int dest) {
    std::map<int, int> got = deliveries();
    std::vector<int> out;
    std::lock_guard lock(mutex_);
    for (const auto& [n, m] : sent_) {
      if ((dest == 0 || m.destination == dest) && m.destination != kNowhere && got.count(n) == 0) out.push_back(n);
    }
    return out;
  }

  GatewayFleet fleet_;
  std::unique_ptr<StreamSubscriber> shore_statuses_, a_commands_, b_commands_, b_plans_;
  std::mutex mutex_;
  std::map<int, TracedMessage> sent_;  // by number
  std::vector<std::string> wrong_;
};

std::string numbers(const std::vector<int>& list) {
  std::string out;
  for (int n : list) out += (out.empty() ? "" : ", ") + std::to_string(n);
  return "[" + out + "]";
}

TEST_F(GatewayFleetTest, ShoreAndVehiclesExchangeEverythingOnceThroughABuoyKilledWhileHoldingMessages) {
  const auto began = std::chrono::steady_clock::now();
  ASSERT_NO_FATAL_FAILURE(fleet_.start_all());
  shore_statuses_ = std::make_unique<StreamSubscriber>(fleet_.socket(kShore), "example.Status");
  a_commands_ = std::make_unique<StreamSubscriber>(fleet_.socket(kVehicleA), "example.Command");
  b_commands_ = std::make_unique<StreamSubscriber>(fleet_.socket(kVehicleB), "example.Command");
  b_plans_ = std::make_unique<StreamSubscriber>(fleet_.socket(kVehicleB), "fleet.SurveyPlan");
  CustodyWatch watch({{kBuoy, fleet_.socket(kBuoy)}, {kVehicleA, fleet_.socket(kVehicleA)}});

  // The loop, and the plan the buoy cannot decode, go first.
  command(kNowhere, kLoopCommand);
  const std::string plan_json =
      send(kShore, kVehicleB, "fleet.SurveyPlan", kPlan,
           R"("plan": 777, "x0": -1234.5, "y0": 987.6, "x1": 4321.0, "y1": -55.5, "depth": 42.5, "label": "lawnmower-7")");
  // Statuses from both vehicles all along (they also teach the buoy the way
  // to B again after each of its restarts).
  std::atomic<bool> reporting{true};
  std::thread vehicles([&] {
    for (int i = 0; reporting; ++i) {
      status(kVehicleA, 3000 + i);
      status(kVehicleB, 4000 + i);
      for (auto t = 0ms; t < kStatusPeriod && reporting; t += 100ms) std::this_thread::sleep_for(100ms);
    }
  });
  struct StopReporting {  // also when an ASSERT leaves the test early
    std::atomic<bool>& on;
    std::thread& thread;
    ~StopReporting() {
      on = false;
      if (thread.joinable()) thread.join();
    }
  } stop_reporting{reporting, vehicles};

  // The storm: a round of Commands, a random pause, then the buoy dies as
  // soon as it holds something, and comes back on its data dir.
  const int kills = kills_wanted();
  std::mt19937 random(std::random_device{}());
  std::uniform_int_distribution<int> pause_ms(1000, 4000);
  std::vector<uint64_t> held_at_kill;
  int next_command = 1000;
  for (int k = 0; k < kills && !HasFatalFailure(); ++k) {
    command(kVehicleA, next_command++);
    command(kVehicleB, next_command++);
    std::this_thread::sleep_for(std::chrono::milliseconds(pause_ms(random)));
    uint64_t held = 0;
    ASSERT_TRUE(wait_until(
        [&] {
          held = routes(fleet_.socket(kBuoy)).custody_held();
          return held > 0 && held != ~0ull;
        },
        30s, 20ms))
        << "kill " << k + 1 << ": the buoy never held a message" << fleet_.all_logs();
    fleet_.kill(kBuoy);
    held_at_kill.push_back(held);
    ASSERT_NO_FATAL_FAILURE(fleet_.start(kBuoy));
  }
  // Six more rounds of Statuses after the last restart (B's teach the buoy
  // the way to B once more), with Commands in every other one: A's custody
  // queue holds messages for both its next hops at once (B's Statuses for
  // the buoy, the shore's Commands for B), as a relay's does. Then no new
  // traffic: the backlog drains.
  for (int round = 0; round < 6; ++round) {
    if (round % 2 == 0) command(kVehicleA, next_command++), command(kVehicleB, next_command++);
    std::this_thread::sleep_for(kStatusPeriod);
  }
  reporting = false;
  if (vehicles.joinable()) vehicles.join();

  // Generous: custody's head-of-line wait at A (see kRelayWaitBoundS's
  // check below) stretches the drain to a minute or two.
  EXPECT_TRUE(wait_until([&] { return missing(0).empty(); }, 150s, 250ms))
      << "never delivered: " << numbers(missing(kVehicleA)) << " (to A), " << numbers(missing(kVehicleB))
      << " (to B), " << numbers(missing(kShore)) << " (to the shore)" << fleet_.all_logs();
  // Nothing held anywhere once all is delivered and the loop is over.
  EXPECT_TRUE(wait_until(
      [&] {
        return routes(fleet_.socket(kBuoy)).custody_held() == 0 &&
               routes(fleet_.socket(kVehicleA)).custody_held() == 0 &&
               routes(fleet_.socket(kVehicleA)).hop_limit_dropped() >= 1;
      },
      40s, 250ms))
      << "buoy:\n" << describe(routes(fleet_.socket(kBuoy))) << "vehicle A:\n"
      << describe(routes(fleet_.socket(kVehicleA))) << fleet_.all_logs();
  // Room for a copy that would come twice: one more acoustic cycle.
  std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int>(3 * kAcousticSlotS * 1000)));

  // Once each, end to end, and only where they were sent.
  const std::map<int, int> copies = deliveries();
  std::vector<int> twice;
  for (const auto& [n, c] : copies) {
    if (c > 1) twice.push_back(n);
  }
  EXPECT_TRUE(twice.empty()) << "delivered more than once: " << numbers(twice) << fleet_.all_logs();
  EXPECT_TRUE(wrong_.empty()) << wrong_.size() << " delivered where they were not sent, first: " << wrong_.front();
  EXPECT_TRUE(missing(0).empty()) << "lost: " << numbers(missing(0)) << fleet_.all_logs();
  EXPECT_EQ(held_at_kill.size(), static_cast<size_t>(kills));
  // Each origin heard its first hop's ACK once, and the destination's
  // end-to-end ack once (the receipts travel back with custody, through the
  // buoy's restarts too).
  EXPECT_TRUE(wait_until(
      [&] {
        for (const auto& [n, m] : sent_) {
          if (m.destination != kNowhere && origin_acks(fleet_.socket(m.origin), m.origin_id).end_to_end_acks == 0) {
            return false;
          }
        }
        return true;
      },
      60s, 500ms));
  int end_to_end = 0;
  for (const auto& [n, m] : sent_) {
    if (m.destination == kNowhere) continue;
    const OriginAcks acks = origin_acks(fleet_.socket(m.origin), m.origin_id);
    EXPECT_EQ(acks.hop_acks, 1) << m.what << " " << n << " at " << GatewayFleet::name(m.origin);
    EXPECT_EQ(acks.end_to_end_acks, 1) << m.what << " " << n << " at " << GatewayFleet::name(m.origin);
    end_to_end += acks.end_to_end_acks;
  }
  std::cout << "gateway fleet: " << end_to_end << " end-to-end acks back at their origins\n";

  // The plan: the buoy never loaded its type, yet B got the shore's DCCL
  // bytes: they crossed the satellite inside an MT as the shore encoded
  // them, the buoy held them in custody, and B's copy encodes to them again.
  EXPECT_FALSE(loads_type(fleet_.socket(kBuoy), "fleet.SurveyPlan"));
  const std::string plan_bytes = encode(fleet_.socket(kShore), "fleet.SurveyPlan", plan_json, "");
  ASSERT_FALSE(plan_bytes.empty());
  bool in_an_mt = false;
  for (const auto& mt : fleet_.directip().mt_submissions()) in_an_mt |= mt.payload.find(plan_bytes) != std::string::npos;
  EXPECT_TRUE(in_an_mt) << "the plan's DCCL bytes are in no MT the shore submitted";
  bool held_by_buoy = false;
  for (const CustodySighting& s : watch.sightings()) {
    held_by_buoy |= s.node == kBuoy && s.origin == kShore && s.destination == kVehicleB &&
                    s.seq == static_cast<int>(sent_[kPlan].origin_id & 0xffff);
  }
  EXPECT_TRUE(held_by_buoy) << "the plan was never seen in the buoy's custody";
  const auto plans = b_plans_->received();
  ASSERT_EQ(plans.size(), 1u);
  EXPECT_EQ(encode(fleet_.socket(kVehicleB), "fleet.SurveyPlan", "", plans.front().payload()), plan_bytes)
      << plans.front().json();
  EXPECT_NE(plans.front().json().find("lawnmower-7"), std::string::npos) << plans.front().json();

  // The loop: node 20's Command went shore -> buoy -> A -> buoy -> A and
  // ended at A, at hop 4 of 4, acknowledged there (nothing left held).
  const v1::ListRoutesResponse a_routes = routes(fleet_.socket(kVehicleA));
  EXPECT_GE(a_routes.hop_limit_dropped(), 1u) << describe(a_routes);
  EXPECT_NE(fleet_.logs(kVehicleA).find("message 1/" + std::to_string(sent_[kLoopCommand].origin_id & 0xffff) +
                                        " for node 20 dropped after 4 hops"),
            std::string::npos)
      << fleet_.logs(kVehicleA);

  // Learned routes: the buoy hears A and learned B through A; A hears B;
  // the shore learned both vehicles through the buoy from what it forwards.
  const v1::ListRoutesResponse buoy_routes = routes(fleet_.socket(kBuoy)), shore_routes = routes(fleet_.socket(kShore));
  EXPECT_TRUE(has_route(buoy_routes, kVehicleA, kVehicleA, "acoustic", "heard")) << describe(buoy_routes);
  EXPECT_TRUE(has_route(buoy_routes, kVehicleB, kVehicleA, "acoustic", "relayed")) << describe(buoy_routes);
  EXPECT_TRUE(has_route(a_routes, kVehicleB, kVehicleB, "acoustic", "heard")) << describe(a_routes);
  EXPECT_TRUE(has_route(shore_routes, kVehicleA, kBuoy, "iridium", "relayed")) << describe(shore_routes);
  EXPECT_TRUE(has_route(shore_routes, kVehicleB, kBuoy, "iridium", "relayed")) << describe(shore_routes);

  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  std::map<int, std::vector<v1::Event>> events;
  for (int node : {kShore, kBuoy, kVehicleA, kVehicleB}) events[node] = node_events(fleet_.socket(node));
  std::vector<TracedMessage> traced;
  for (const auto& [n, m] : sent_) {
    if (m.destination != kNowhere) traced.push_back(m);
  }
  const NetworkFigures figures = network_figures(traced, watch.sightings(), events);
  std::map<int, std::string> names;
  for (int node : {kShore, kBuoy, kVehicleA, kVehicleB}) names[node] = GatewayFleet::name(node);
  figures.print(std::cout, names);
  std::cout << "  buoy SIGKILLed " << kills << " times, holding";
  for (uint64_t held : held_at_kill) std::cout << " " << held;
  std::cout << " message(s); wall time " << wall_s << " s\n";
  for (int node : {kShore, kBuoy, kVehicleA, kVehicleB}) {
    std::cout << "  routes of " << names[node] << ":\n" << describe(routes(fleet_.socket(node)));
  }
  EXPECT_EQ(figures.delivered, figures.messages);
  EXPECT_GT(figures.traced, 0);
  // QueueStats.delivered, as the API exports it, counts the end-to-end acks
  // each origin logged (the shore and vehicle A are never killed: both
  // count since the start).
  for (int node : {kShore, kVehicleA}) {
    grpc::ClientContext context;
    v1::QueueStatsResponse stats;
    ASSERT_TRUE(api(fleet_.socket(node))->QueueStats(&context, {}, &stats).ok());
    uint64_t counted = 0;
    for (const v1::QueueStatsEntry& q : stats.queues()) counted += q.delivered();
    uint64_t logged = 0;
    for (const v1::Event& e : node_events(fleet_.socket(node), {"delivered"})) logged += e.kind() == "delivered";
    EXPECT_EQ(counted, logged) << names[node];
    EXPECT_GT(counted, 0u) << names[node];
  }
  // Vehicle A (never killed, always hearing both neighbours) sends what it
  // holds for others within kRelayWaitBoundS of taking custody.
  const HopDelay a_wait = figures.relay_wait.count(kVehicleA) ? figures.relay_wait.at(kVehicleA) : HopDelay{};
  EXPECT_LE(a_wait.max_s, kRelayWaitBoundS)
      << "vehicle A held custody message " << (a_wait.n ? figures.relay_worst_id.at(kVehicleA) : 0) << " " << a_wait.max_s
      << " s before sending it on (bound " << kRelayWaitBoundS << " s, 5 acoustic cycles): the custody message "
      << "at the head of A's custody queue, for one next hop, holds the ones behind it for the other whenever A's "
      << "transmission goes to the other next hop (a transmission takes only the run of custody messages at the "
      << "queue's head that share its next hop)";
}

}  // namespace
}  // namespace acomms::testing
