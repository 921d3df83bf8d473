// A whole network in one process on the simulated clock: three nodes, each
// with its own queues, auto-discovery MAC and sim driver on one simulated
// acoustic channel. They must discover each other and settle on one
// collision-free cycle, then carry DCCL messages through the queues, with
// acks clearing the senders' queues. Hours of network time run in seconds.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "core/scheduler.h"
#include "net_status_proto.h"
#include "link/link_controller.h"
#include "mac/auto_discovery_mac.h"
#include "mac/mac_factory.h"
#include "queue/memory_journal.h"
#include "queue/submitter.h"
#include "sim/sim_channel.h"
#include "sim/sim_driver.h"

namespace acomms {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;
using namespace std::chrono_literals;


// 2025-06-01 10:00:00 UTC: an ordinary morning, far from midnight.
constexpr int64_t kStart = 1'748'772'000;

struct Node {
  Node(int32_t id, double x, core::SimulatedScheduler& scheduler, std::shared_ptr<drivers::SimChannel> channel,
       const std::string& proto) {
    codec.load(proto);
    v1::QueueConfig queue_config;
    pb::TextFormat::ParseFromString(
        R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } })", &queue_config);
    queues = std::make_unique<queue::QueueManager>(codec, queue_config, id, scheduler.clock(), journal);

    driver_config.set_name("sim");
    driver_config.set_modem_id(static_cast<uint32_t>(id));
    driver_config.mutable_sim()->mutable_position()->set_x(x);
    driver = std::make_unique<drivers::SimDriver>(driver_config, scheduler, channel);

    v1::MacConfig mac_config;
    pb::TextFormat::ParseFromString(
        R"(name: "auto_discovery" slot_seconds: 10 rate: 0 coolness: 4 expire_cycles: 20 blank_rule: "anywhere")",
        &mac_config);
    mac = mac::make_mac(mac_config, id, scheduler);
    link = std::make_unique<link::LinkController>(
        id, *queues, *mac, *driver, [this](queue::ReceivedMessage m, const v1::ModemTransmission&) {
          received.push_back(m.message->ShortDebugString());
        });
  }

  std::vector<int32_t> cycle_ids() const {
    std::vector<int32_t> ids;
    for (const mac::Slot& slot : mac->cycle()) ids.push_back(slot.src);
    return ids;
  }

  void submit(int32_t src, int32_t dest, int battery) {
    auto m = codec.new_message("net.Status");
    pb::TextFormat::ParseFromString("src: " + std::to_string(src) + " dest: " + std::to_string(dest) +
                                        " battery: " + std::to_string(battery),
                                    m.get());
    // This thread is the core and MemoryJournal stores at once: answered
    // before submit() returns.
    queue::Submitter submitter(*queues, [](std::function<void()> work) { work(); });
    queue::SubmitResult result;
    submitter.submit(*m, 0, [&result](queue::SubmitResult r) { result = std::move(r); });
    ASSERT_TRUE(result.ok()) << result.text;
  }

  dccl::Codec codec;
  queue::MemoryJournal journal;
  std::unique_ptr<queue::QueueManager> queues;
  v1::DriverConfig driver_config;
  std::unique_ptr<drivers::SimDriver> driver;
  std::unique_ptr<mac::Mac> mac;
  std::unique_ptr<link::LinkController> link;
  std::vector<std::string> received;
};

TEST(SimulatedNetwork, ThreeNodesDiscoverEachOtherThenExchangeMessagesWithAcks) {
  fs::path dir = fs::temp_directory_path() / ("acomms-net-" + std::to_string(::getpid()));
  fs::create_directories(dir);
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
  fs::remove_all(dir);
}

}  // namespace
}  // namespace acomms
