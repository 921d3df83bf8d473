// A whole network in one process on the simulated clock: three nodes, each
// with its own queues, auto-discovery MAC and sim driver on one simulated
// acoustic channel. They must discover each other and settle on one
// collision-free cycle, then carry DCCL messages through the queues, with
// acks clearing the senders' queues. Hours of network time run in seconds.

#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "core/scheduler.h"
#include "mac/auto_discovery_mac.h"
#include "net_status_proto.h"
#include "sim_node.h"
#include "temp_dir.h"

namespace acomms {
namespace {

using namespace std::chrono_literals;


// 2025-06-01 10:00:00 UTC: an ordinary morning, far from midnight.
constexpr int64_t kStart = 1'748'772'000;

struct Node : testing::SimNode {
  Node(int32_t id, double x, core::SimulatedScheduler& scheduler, std::shared_ptr<drivers::SimChannel> channel,
       const std::string& proto)
      : SimNode({.id = id,
                 .x = x,
                 .proto = proto,
                 .queue_config =
                     R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } })",
                 .mac_config = R"(name: "auto_discovery" slot_seconds: 10 rate: 0 coolness: 4 expire_cycles: 20 )"
                               R"(blank_rule: "anywhere")"},
                scheduler, std::move(channel), [this](queue::ReceivedMessage m, const v1::ModemTransmission&) {
                  received.push_back(m.message->ShortDebugString());
                }) {}

  std::vector<int32_t> cycle_ids() const {
    std::vector<int32_t> ids;
    for (const mac::Slot& slot : mac->cycle()) ids.push_back(slot.src);
    return ids;
  }

  void submit(int32_t src, int32_t dest, int battery) {
    SimNode::submit("net.Status", "src: " + std::to_string(src) + " dest: " + std::to_string(dest) +
                                      " battery: " + std::to_string(battery));
  }

  std::vector<std::string> received;
};

TEST(SimulatedNetwork, ThreeNodesDiscoverEachOtherThenExchangeMessagesWithAcks) {
  testing::TempDir dir("acomms-net");
  std::ofstream(dir / "net.proto") << testing::kNetStatusProto;

  core::SimulatedScheduler scheduler{core::Clock::time_point(std::chrono::seconds(kStart))};
  auto channel = drivers::SimChannel::create(/*seed=*/7);
  // 7-bit ids, a few hundred metres apart (well inside one 10 s slot).
  std::map<int32_t, std::unique_ptr<Node>> nodes;
  const std::vector<std::pair<int32_t, double>> layout = {{23, 0}, {5, 400}, {96, 900}};
  for (const auto& [id, x] : layout) {
    nodes[id] = std::make_unique<Node>(id, x, scheduler, channel, (dir / "net.proto").string());
  }
  // They power on at different times.
  scheduler.run_for(3s);
  nodes[23]->link->start();
  scheduler.run_for(47s);
  nodes[5]->link->start();
  scheduler.run_for(95s);
  nodes[96]->link->start();

  // Converged: every node's cycle holds all three ids (plus its blank), in
  // the same order, and it stays that way.
  const std::vector<int32_t> all = {5, 23, 96};
  auto converged = [&] {
    for (auto& [id, node] : nodes) {
      std::vector<int32_t> heard = static_cast<mac::AutoDiscoveryMac&>(*node->mac).known_ids();
      if (heard != all) return false;
    }
    return true;
  };
  int waited_cycles = 0;
  while (!converged() && waited_cycles < 100) {
    scheduler.run_for(40s);  // one 4-slot cycle
    ++waited_cycles;
  }
  ASSERT_TRUE(converged()) << "no shared cycle after " << waited_cycles << " cycles";
  // Let the views settle into the same cycle, then demand silence of
  // collisions: every node hears both others in every cycle from now on.
  scheduler.run_for(200s);
  std::map<int32_t, uint64_t> collisions_before;
  for (auto& [id, node] : nodes) collisions_before[id] = (node->driver->stats().lost_collision + node->driver->stats().lost_half_duplex);
  scheduler.run_for(400s);
  for (auto& [id, node] : nodes) {
    EXPECT_EQ(static_cast<mac::AutoDiscoveryMac&>(*node->mac).known_ids(), all) << "node " << id;
    EXPECT_EQ((node->driver->stats().lost_collision + node->driver->stats().lost_half_duplex), collisions_before[id]) << "node " << id << " still collides";
  }

  // Now traffic: each node sends a unicast message to each other node.
  int battery = 0;
  for (auto& [src, node] : nodes) {
    for (const auto& [dest, other] : nodes) {
      if (dest != src) node->submit(src, dest, ++battery);
    }
  }
  scheduler.run_for(600s);
  for (auto& [id, node] : nodes) {
    EXPECT_EQ(node->received.size(), 2u) << "node " << id << " received " << node->received.size();
    for (const std::string& text : node->received) {
      EXPECT_NE(text.find("dest: " + std::to_string(id) + " "), std::string::npos) << text;
    }
    const queue::QueueStats stats = node->queues->stats("net.Status");
    EXPECT_EQ(stats.acked, 2u) << "node " << id;
    EXPECT_EQ(node->queues->find_queue("net.Status")->size(), 0u) << "node " << id << " still holds messages";
    EXPECT_EQ(node->journal.stored(), 0u);
  }
  std::printf("converged after %d cycles (of 40 s) from the last power-on\n", waited_cycles);
}

}  // namespace
}  // namespace acomms
