// One node holding two links, on the simulated clock: an "acoustic" link
// and a second one (here another sim channel, standing in for a satellite
// link), each with its own supervised driver and fixed TDMA MAC, over one
// set of queues and one choice of link (link/link_choice.h). A peer with
// id 2 is on each channel (two SimNodes, one per channel).
//
// Shown: a driver that fails on one link leaves the other sending, and its
// messages still arrive; a type routed "acoustic, then the other link"
// falls back after the configured silence and comes back when the
// acoustic peer is heard again; each message is acknowledged once.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <set>

#include "core/scheduler.h"
#include "link/driver_supervisor.h"
#include "link/link_choice.h"
#include "mac/mac_factory.h"
#include "net_status_proto.h"
#include "sim_node.h"
#include "submit_now.h"
#include "temp_dir.h"

namespace acomms {
namespace {

using namespace std::chrono_literals;

constexpr int64_t kStart = 1'748'772'000;  // 2025-06-01 10:00:00 UTC
constexpr const char* kCycle = R"(name: "fixed" slot { src: 1 rate: 0 seconds: 10 } slot { src: 2 rate: 0 seconds: 10 })";
constexpr const char* kQueue = R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } })";

// A sim driver that can be broken: then it fails its work and every start.
class BreakableDriver final : public link::Driver {
 public:
  BreakableDriver(std::unique_ptr<link::Driver> inner, std::shared_ptr<bool> broken)
      : inner_(std::move(inner)), broken_(std::move(broken)) {}
  void start(link::DriverCallbacks callbacks) override {
    if (*broken_) throw link::DriverError("modem unplugged");
    inner_->start(std::move(callbacks));
  }
  void stop() override { inner_->stop(); }
  void do_work() override {
    if (*broken_) throw link::DriverError("modem unplugged");
    inner_->do_work();
  }
  void initiate_transmission(const v1::ModemTransmission& t) override {
    if (*broken_) throw link::DriverError("modem unplugged");
    inner_->initiate_transmission(t);
  }
  std::chrono::nanoseconds packet_air_time(int32_t rate, uint32_t frames) const override {
    return inner_->packet_air_time(rate, frames);
  }
  std::chrono::nanoseconds ack_time(int32_t rate) const override { return inner_->ack_time(rate); }
  double sound_speed() const override { return inner_->sound_speed(); }

 private:
  std::unique_ptr<link::Driver> inner_;
  std::shared_ptr<bool> broken_;
};

// The vehicle (id 1): one queue manager, two links.
struct Vehicle {
  struct Link {
    v1::DriverConfig driver_config;
    std::shared_ptr<bool> broken = std::make_shared<bool>(false);
    std::unique_ptr<link::DriverSupervisor> driver;
    std::unique_ptr<mac::Mac> mac;
    std::unique_ptr<link::LinkController> controller;
  };

  Vehicle(core::SimulatedScheduler& scheduler, const std::string& proto, const std::string& queue_text,
          std::vector<std::shared_ptr<drivers::SimChannel>> channels) {
    codec.load(proto);
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(queue_text, &queue_config));
    queues = std::make_unique<queue::QueueManager>(codec, queue_config, 1, scheduler.clock(), journal);
    std::vector<v1::LinkConfig> configs(2);
    configs[0].set_name("acoustic");
    configs[1].set_name("sat");
    choice = std::make_unique<link::LinkChoice>(
        link::LinkChoice::from_config(configs, queue_config, scheduler.clock().now_seconds()));
    for (int i = 0; i < 2; ++i) {
      auto& l = links.emplace_back(std::make_unique<Link>());
      l->driver_config.set_name("sim");
      l->driver_config.set_modem_id(1);
      link::SupervisorOptions options;
      options.driver_name = configs[i].name();
      l->driver = std::make_unique<link::DriverSupervisor>(
          [&scheduler, l = l.get(), channel = channels[i]]() -> std::unique_ptr<link::Driver> {
            if (*l->broken) throw link::DriverError("modem unplugged");
            return std::make_unique<BreakableDriver>(
                std::make_unique<drivers::SimDriver>(l->driver_config, scheduler, channel), l->broken);
          },
          scheduler, options);
      v1::MacConfig mac_config;
      EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(kCycle, &mac_config));
      l->mac = mac::make_mac(mac_config, 1, scheduler);
      link::LinkOptions link_options;
      link_options.clock = &scheduler.clock();
      link_options.scheduler = &scheduler;
      link_options.choice = choice.get();
      link_options.link_index = i;
      l->controller = std::make_unique<link::LinkController>(
          1, *queues, *l->mac, *l->driver, [](queue::ReceivedMessage, const v1::ModemTransmission&) {},
          link_options);
      l->driver->set_status_callback([c = l->controller.get()](const link::DriverStatus& status) {
        c->on_driver_state(status.state == link::DriverState::kRunning);
      });
    }
  }
  ~Vehicle() {
    for (auto& l : links) {
      l->controller->stop();
      l->driver->set_status_callback(nullptr);
    }
  }

  void submit(int battery) {
    auto m = codec.new_message("net.Status");
    google::protobuf::TextFormat::ParseFromString("src: 1 dest: 2 battery: " + std::to_string(battery), m.get());
    EXPECT_TRUE(testing::submit_now(*queues, *m).ok());
  }

  dccl::Codec codec;
  v1::QueueConfig queue_config;
  queue::MemoryJournal journal;
  std::unique_ptr<queue::QueueManager> queues;
  std::unique_ptr<link::LinkChoice> choice;
  std::vector<std::unique_ptr<Link>> links;
};

struct Peer : testing::SimNode {
  Peer(core::SimulatedScheduler& scheduler, std::shared_ptr<drivers::SimChannel> channel, const std::string& proto)
      : SimNode({.id = 2, .x = 500, .proto = proto, .queue_config = kQueue, .mac_config = kCycle}, scheduler,
                std::move(channel), [this](queue::ReceivedMessage m, const v1::ModemTransmission&) {
                  batteries.push_back(
                      m.message->GetReflection()->GetInt32(*m.message, m.message->GetDescriptor()->FindFieldByName("battery")));
                }) {}
  std::vector<int> batteries;
};

class SeveralLinksNetwork : public ::testing::Test {
 protected:
  void build(const std::string& queue_text) {
    std::ofstream(dir_ / "net.proto") << testing::kNetStatusProto;
    const std::string proto = (dir_ / "net.proto").string();
    vehicle_ = std::make_unique<Vehicle>(scheduler_, proto, queue_text,
                                         std::vector<std::shared_ptr<drivers::SimChannel>>{acoustic_, sat_});
    peer_acoustic_ = std::make_unique<Peer>(scheduler_, acoustic_, proto);
    peer_sat_ = std::make_unique<Peer>(scheduler_, sat_, proto);
    for (auto& l : vehicle_->links) l->controller->start();
    peer_acoustic_->link->start();
    peer_sat_->link->start();
  }
  void TearDown() override {
    if (peer_acoustic_) peer_acoustic_->link->stop();
    if (peer_sat_) peer_sat_->link->stop();
  }
  int acked() {
    int n = 0;
    for (const auto& e : vehicle_->journal.events()) n += e.kind == queue::QueueEventKind::kAcked;
    return n;
  }
  size_t queued() { return vehicle_->queues->find_queue("net.Status")->size(); }

  testing::TempDir dir_{"acomms-links"};
  core::SimulatedScheduler scheduler_{core::Clock::time_point(std::chrono::seconds(kStart))};
  std::shared_ptr<drivers::SimChannel> acoustic_ = drivers::SimChannel::create(/*seed=*/3);
  std::shared_ptr<drivers::SimChannel> sat_ = drivers::SimChannel::create(/*seed=*/4);
  std::unique_ptr<Vehicle> vehicle_;
  std::unique_ptr<Peer> peer_acoustic_;
  std::unique_ptr<Peer> peer_sat_;
};

TEST_F(SeveralLinksNetwork, DriverFailingOnOneLinkLeavesTheOtherSending) {
  build(kQueue);
  for (int i = 0; i < 5; ++i) vehicle_->submit(i);
  scheduler_.run_for(120s);
  EXPECT_EQ(queued(), 0u);
  EXPECT_EQ(acked(), 5) << "each message acknowledged once";

  *vehicle_->links[0]->broken = true;  // the acoustic modem is unplugged
  scheduler_.run_for(30s);
  EXPECT_NE(vehicle_->links[0]->driver->status().state, link::DriverState::kRunning);
  EXPECT_EQ(vehicle_->links[1]->driver->status().state, link::DriverState::kRunning);
  const size_t acoustic_before = peer_acoustic_->batteries.size();
  const uint64_t sat_sent_before = vehicle_->links[1]->controller->stats().transmissions_sent;
  for (int i = 10; i < 15; ++i) vehicle_->submit(i);
  scheduler_.run_for(200s);
  EXPECT_EQ(queued(), 0u) << "the other link did not carry the messages";
  EXPECT_EQ(acked(), 10);
  EXPECT_EQ(peer_acoustic_->batteries.size(), acoustic_before) << "the broken link still delivered";
  std::set<int> on_sat(peer_sat_->batteries.begin(), peer_sat_->batteries.end());
  for (int i = 10; i < 15; ++i) EXPECT_TRUE(on_sat.count(i)) << "message " << i << " never arrived";
  EXPECT_GT(vehicle_->links[1]->controller->stats().transmissions_sent, sat_sent_before);
  EXPECT_GE(vehicle_->links[0]->driver->status().failures, 2u) << "the supervisor keeps retrying the broken one";
}

TEST_F(SeveralLinksNetwork, RoutedTypeFallsBackAfterTheSilenceAndComesBackWhenHeard) {
  build(std::string(R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } )") +
        R"(route { dest: 2 link: "acoustic" link: "sat" fallback_after_s: 60 } })");
  for (int i = 0; i < 3; ++i) vehicle_->submit(i);
  scheduler_.run_for(100s);
  EXPECT_EQ(peer_acoustic_->batteries, (std::vector<int>{2, 1, 0})) << "newest first, on acoustic";
  EXPECT_TRUE(peer_sat_->batteries.empty()) << "the second link carried a message while acoustic reached node 2";

  // The acoustic peer goes silent: for 60 s the vehicle keeps to acoustic
  // (unacked, retried), then the other link takes over.
  peer_acoustic_->link->stop();
  const double silent_from = scheduler_.clock().now_seconds();
  vehicle_->submit(10);
  scheduler_.run_for(45s);
  EXPECT_TRUE(peer_sat_->batteries.empty()) << "fell back before the configured silence";
  EXPECT_EQ(queued(), 1u);
  scheduler_.run_for(60s);
  EXPECT_EQ(peer_sat_->batteries, (std::vector<int>{10}));
  EXPECT_EQ(queued(), 0u);
  EXPECT_EQ(vehicle_->choice->carrier("net.Status", 2, scheduler_.clock().now_seconds()), 1);
  EXPECT_GT(scheduler_.clock().now_seconds() - silent_from, 60);

  // Heard again (its empty slot broadcasts): acoustic carries once more.
  peer_acoustic_->link->start();
  scheduler_.run_for(25s);
  vehicle_->submit(20);
  scheduler_.run_for(40s);
  EXPECT_EQ(peer_acoustic_->batteries.back(), 20);
  EXPECT_EQ(peer_sat_->batteries, (std::vector<int>{10})) << "the second link kept carrying after acoustic came back";
  EXPECT_EQ(acked(), 5) << "each message acknowledged once";
}

}  // namespace
}  // namespace acomms
