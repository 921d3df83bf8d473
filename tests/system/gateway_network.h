// Gateways on the simulated clock: a shore (1), a buoy (2) and a vehicle
// (3). The shore and the buoy share one channel ("sat"), the buoy and the
// vehicle another ("acoustic"): the shore never hears the vehicle. Each
// node has its own queues, an in-memory journal that outlives a restart,
// a Forwarder (route/forwarder.h) and one fixed-TDMA link per channel.
// The fixture the system.GatewayNetwork tests share (one file per theme:
// gateway_network_test.cpp, gateway_custody_test.cpp, ...).

#pragma once
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <memory>

#include "core/scheduler.h"
#include "link/link_choice.h"
#include "link/link_controller.h"
#include "mac/mac_factory.h"
#include "modem_ack_driver.h"
#include "queue/memory_journal.h"
#include "route/forwarder.h"
#include "sim/sim_driver.h"
#include "submit_now.h"
#include "temp_dir.h"

namespace acomms::gateway_test {

inline constexpr int64_t kStart = 1'748'772'000;  // 2025-06-01 10:00:00 UTC

// net.Status everywhere; net.Command only on the shore and the vehicle.
inline constexpr const char* kStatusProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package net;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 10 max_bytes: 32 };
  required int32 src = 1 [(dccl.field) = { min: 0 max: 127 }];
  required int32 dest = 2 [(dccl.field) = { min: 0 max: 127 }];
  required int32 battery = 3 [(dccl.field) = { min: 0 max: 100 }];
}
)";
inline constexpr const char* kCommandProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package net;
message Command {
  option (dccl.msg) = { codec_version: 4 id: 20 max_bytes: 16 };
  required int32 src = 1 [(dccl.field) = { min: 0 max: 127 }];
  required int32 dest = 2 [(dccl.field) = { min: 0 max: 127 }];
  required int32 code = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
)";
inline constexpr const char* kQueues =
    R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } })";
inline constexpr const char* kCommandQueues =
    R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } }
       type { type: "net.Command" roles { source_field: "src" destination_field: "dest" } })";

// A journal kept in memory whose appends a test decides (subclasses):
// what a store fault does to a gateway.
class JournalInMemory : public queue::MessageJournal {
 public:
  using MessageJournal::append;
  void record(const queue::QueueEvent& event) override { inner.record(event); }
  std::vector<queue::JournalMessage> load() override { return inner.load(); }
  std::vector<queue::QueueEvent> received_since(double since) override { return inner.received_since(since); }
  std::vector<queue::QueueEvent> authenticated_since(double since) override {
    return inner.authenticated_since(since);
  }
  std::vector<queue::RoutedIdentity> routed_since(double now) override { return inner.routed_since(now); }
  void flush() override {}
  int64_t last_received_seq() override { return inner.last_received_seq(); }
  void when_committed(Committed committed) override { committed(nullptr); }
  uint64_t events_not_stored() const override { return 0; }

  queue::MemoryJournal inner;
};

// A journal whose appends can be made to fail (a full disk).
class FailingJournal final : public JournalInMemory {
 public:
  using MessageJournal::append;
  void append(queue::JournalMessage message, Appended appended) override {
    if (fail_appends) return appended(0, std::make_exception_ptr(std::runtime_error("disk full")));
    inner.append(std::move(message), std::move(appended));
  }

  bool fail_appends = false;
};

struct LinkSpec {
  std::string name;
  std::shared_ptr<drivers::SimChannel> channel;
  std::string cycle;  // v1::MacConfig text
  double cost = 0;    // LinkConfig.cost
  bool modem_acks = false;  // the modem ACKs in hardware (modem_ack_driver.h)
};

// One node: queues, forwarder and one link per LinkSpec. The journal is
// the test's, so that a rebuilt node finds what its last life stored.
struct GatewayNode {
  GatewayNode(int32_t id, const std::vector<std::string>& protos, const std::string& queue_text,
              const std::string& routing_text, const std::vector<LinkSpec>& specs,
              core::SimulatedScheduler& scheduler, queue::MessageJournal& journal,
              route::RouteJournal* route_journal = nullptr) {
    for (const std::string& proto : protos) codec.load(proto);
    v1::QueueConfig queue_config;
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(queue_text, &queue_config));
    v1::RoutingConfig routing;
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(routing_text, &routing)) << routing_text;
    queues = std::make_unique<queue::QueueManager>(codec, queue_config, id, scheduler.clock(), journal);
    std::vector<std::string> names;
    std::vector<v1::LinkConfig> configs;
    for (const LinkSpec& spec : specs) {
      names.push_back(spec.name);
      configs.emplace_back().set_name(spec.name);
      configs.back().set_cost(spec.cost);
    }
    // The journal here completes at once, on the core: nothing to post.
    forwarder = std::make_unique<route::Forwarder>(routing, id, names, codec, *queues, scheduler.clock(), 1800,
                                                   [](std::function<void()> work) { work(); }, route_journal);
    queues->set_routing(forwarder.get());
    queues->restore();
    choice = std::make_unique<link::LinkChoice>(
        link::LinkChoice::from_config(configs, queue_config, scheduler.clock().now_seconds()));
    for (size_t i = 0; i < specs.size(); ++i) {
      Link& l = *links.emplace_back(std::make_unique<Link>());
      v1::DriverConfig driver_config;
      driver_config.set_name("sim");
      driver_config.set_modem_id(static_cast<uint32_t>(id));
      l.driver = std::make_unique<drivers::SimDriver>(driver_config, scheduler, specs[i].channel);
      if (specs[i].modem_acks) l.modem = std::make_unique<ModemAckDriver>(*l.driver);
      v1::MacConfig mac_config;
      EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(specs[i].cycle, &mac_config));
      l.mac = mac::make_mac(mac_config, id, scheduler);
      link::LinkOptions options;
      options.clock = &scheduler.clock();
      options.scheduler = &scheduler;
      options.choice = choice.get();
      options.link_index = static_cast<int>(i);
      // As the daemon: ACKs wait for the store (here at once) and for custody.
      options.after_receipt_durable = [](std::function<void()> then) { then(); };
      l.controller = std::make_unique<link::LinkController>(
          id, *queues, *l.mac, l.modem ? static_cast<link::Driver&>(*l.modem) : *l.driver,
          [this](queue::ReceivedMessage m, const v1::ModemTransmission&) {
            received.push_back({m.type, m.src, m.encoded});
          },
          options);
    }
  }
  ~GatewayNode() { stop(); }
  void start() {
    for (auto& l : links) l->controller->start();
  }
  void stop() {
    for (auto& l : links) l->controller->stop();
  }
  void submit(const std::string& type, const std::string& text) {
    auto m = codec.new_message(type);
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, m.get())) << text;
    queue::SubmitResult result = testing::submit_now(*queues, *m);
    EXPECT_TRUE(result.ok()) << result.text;
  }
  size_t custody_held() const { return forwarder->held(); }

  struct Link {
    std::unique_ptr<drivers::SimDriver> driver;
    std::unique_ptr<ModemAckDriver> modem;  // set: the link's modem ACKs
    std::unique_ptr<mac::Mac> mac;
    std::unique_ptr<link::LinkController> controller;
  };
  struct Received {
    std::string type;
    int32_t src;
    std::string encoded;
  };
  dccl::Codec codec;
  std::unique_ptr<queue::QueueManager> queues;
  std::unique_ptr<route::Forwarder> forwarder;
  std::unique_ptr<link::LinkChoice> choice;
  std::vector<std::unique_ptr<Link>> links;
  std::vector<Received> received;
};

inline constexpr const char* kSatCycle =
    R"(name: "fixed" slot { src: 1 rate: 0 seconds: 10 } slot { src: 2 rate: 0 seconds: 10 })";
inline constexpr const char* kAcousticCycle =
    R"(name: "fixed" slot { src: 2 rate: 0 seconds: 10 } slot { src: 3 rate: 0 seconds: 10 })";

class GatewayNetwork : public ::testing::Test {
 protected:
  GatewayNetwork() {
    std::ofstream(dir_ / "status.proto") << kStatusProto;
    std::ofstream(dir_ / "command.proto") << kCommandProto;
  }
  std::string status_proto() const { return (dir_ / "status.proto").string(); }
  std::string command_proto() const { return (dir_ / "command.proto").string(); }

  void build_shore(const std::string& routing) {
    shore_ = std::make_unique<GatewayNode>(1, std::vector{status_proto(), command_proto()}, kCommandQueues, routing,
                                           std::vector<LinkSpec>{{"sat", sat_, kSatCycle}}, scheduler_,
                                           shore_journal_);
  }
  // The buoy loads net.Status only: it has never heard of net.Command.
  void build_buoy(const std::string& routing) {
    buoy_ = std::make_unique<GatewayNode>(
        2, std::vector{status_proto()}, kQueues, routing,
        std::vector<LinkSpec>{{"sat", sat_, kSatCycle}, {"acoustic", acoustic_, kAcousticCycle}}, scheduler_,
        buoy_journal_);
  }
  void build_buoy_on(const std::string& routing, queue::MessageJournal& journal) {
    buoy_ = std::make_unique<GatewayNode>(
        2, std::vector{status_proto()}, kQueues, routing,
        std::vector<LinkSpec>{{"sat", sat_, kSatCycle}, {"acoustic", acoustic_, kAcousticCycle}}, scheduler_,
        journal);
  }
  void build_vehicle() {
    vehicle_ = std::make_unique<GatewayNode>(3, std::vector{status_proto(), command_proto()}, kCommandQueues, "",
                                             std::vector<LinkSpec>{{"acoustic", acoustic_, kAcousticCycle}},
                                             scheduler_, vehicle_journal_);
  }
  // The operator's plan: vehicle 3 through the buoy over the satellite.
  void build_three(const std::string& buoy_routing = "") {
    build_shore(R"(route { dest: 3 next_hop: 2 link: "sat" })");
    build_buoy(buoy_routing);
    build_vehicle();
  }
  size_t commands_received(const GatewayNode& node) const {
    size_t n = 0;
    for (const auto& r : node.received) n += r.type == "net.Command";
    return n;
  }

  testing::TempDir dir_{"acomms-gateway"};
  core::SimulatedScheduler scheduler_{core::Clock::time_point(std::chrono::seconds(kStart))};
  std::shared_ptr<drivers::SimChannel> sat_ = drivers::SimChannel::create(/*seed=*/11);
  std::shared_ptr<drivers::SimChannel> acoustic_ = drivers::SimChannel::create(/*seed=*/12);
  queue::MemoryJournal shore_journal_, buoy_journal_, vehicle_journal_;
  std::unique_ptr<GatewayNode> shore_, buoy_, vehicle_;
};

}  // namespace acomms::gateway_test
