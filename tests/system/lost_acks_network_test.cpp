// Two nodes on the simulated clock (queues, fixed TDMA, sim drivers on one
// SimChannel) where every ACK is lost for 15 minutes, three times the old
// 300 s duplicate window: the topside resends its Commands and Notes all
// that while, and when the ACKs get through at last each message must have
// reached the vehicle exactly once. Before the window followed the ttl,
// every resend after 300 s was taken as new.

#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "core/scheduler.h"
#include "link/driver.h"
#include "sim_node.h"
#include "temp_dir.h"

namespace acomms {
namespace {

using namespace std::chrono_literals;

// 2025-06-01 10:00:00 UTC.
constexpr int64_t kStart = 1'748'772'000;
constexpr int32_t kVehicle = 1;
constexpr int32_t kTopside = 2;

// Command is stamped (timestamp role); Note is not.
constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package once;
message Command {
  option (dccl.msg) = { codec_version: 4 id: 11 max_bytes: 32 };
  required int32 src = 1 [(dccl.field) = { min: 0 max: 127 }];
  required int32 dest = 2 [(dccl.field) = { min: 0 max: 127 }];
  required int32 seq = 3 [(dccl.field) = { min: 0 max: 1000 }];
  optional double time = 4 [(dccl.field) = { min: 0 max: 2000000000 precision: 0 }];
}
message Note {
  option (dccl.msg) = { codec_version: 4 id: 12 max_bytes: 32 };
  required int32 src = 1 [(dccl.field) = { min: 0 max: 127 }];
  required int32 dest = 2 [(dccl.field) = { min: 0 max: 127 }];
  required int32 seq = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

// The ACKs this node would hear are lost while `losing` is set; the rest
// of what the wrapped driver does passes unchanged.
class AckLosingDriver final : public link::Driver {
 public:
  explicit AckLosingDriver(link::Driver& inner) : inner_(inner) {}
  void start(link::DriverCallbacks callbacks) override {
    auto on_receive = callbacks.on_receive;
    callbacks.on_receive = [this, on_receive](const v1::ModemTransmission& t) {
      if (losing && t.type() == v1::ModemTransmission::ACK) {
        ++lost;
        return;
      }
      on_receive(t);
    };
    inner_.start(std::move(callbacks));
  }
  void stop() override { inner_.stop(); }
  void do_work() override { inner_.do_work(); }
  void initiate_transmission(const v1::ModemTransmission& t) override { inner_.initiate_transmission(t); }

  bool losing = false;
  int lost = 0;

 private:
  link::Driver& inner_;
};

struct Node : testing::SimNode {
  Node(int32_t id, core::SimulatedScheduler& scheduler, std::shared_ptr<drivers::SimChannel> channel,
       const std::string& proto)
      : SimNode(
            {.id = id,
             .x = id == kVehicle ? 500.0 : 0.0,
             .proto = proto,
             // The defaults: duplicate_window_s 300, ttl_s 1800.
             .queue_config =
                 R"(type { type: "once.Command" roles { source_field: "src" destination_field: "dest" timestamp_field: "time" } }
           type { type: "once.Note" roles { source_field: "src" destination_field: "dest" } })",
             .mac_config = R"(name: "fixed" slot { src: 1 rate: 1 seconds: 10 } slot { src: 2 rate: 1 seconds: 10 })",
             .wrap_driver = [](link::Driver& sim) { return std::make_unique<AckLosingDriver>(sim); }},
            scheduler, std::move(channel), [this](queue::ReceivedMessage m, const v1::ModemTransmission&) {
              const auto* seq = m.message->GetDescriptor()->FindFieldByName("seq");
              ++delivered[m.type + " " + std::to_string(m.message->GetReflection()->GetInt32(*m.message, seq))];
            }) {}

  AckLosingDriver& ack_losing() { return static_cast<AckLosingDriver&>(*wrapper); }

  void submit(const std::string& type, int32_t dest, int seq) {
    SimNode::submit(type, "dest: " + std::to_string(dest) + " seq: " + std::to_string(seq));
  }

  std::map<std::string, int> delivered;  // "type seq" -> copies
};

TEST(LostAcksNetwork, AcksLostThreeTimesTheOldWindowStillDeliverEachMessageExactlyOnce) {
  testing::TempDir dir("acomms-lost-acks");
  std::ofstream(dir / "once.proto") << kProto;

  core::SimulatedScheduler scheduler{core::Clock::time_point(std::chrono::seconds(kStart))};
  auto channel = drivers::SimChannel::create(/*seed=*/11);
  Node vehicle(kVehicle, scheduler, channel, (dir / "once.proto").string());
  Node topside(kTopside, scheduler, channel, (dir / "once.proto").string());
  topside.ack_losing().losing = true;
  vehicle.link->start();
  topside.link->start();

  constexpr int kEach = 40;
  for (int seq = 0; seq < kEach; ++seq) {
    topside.submit("once.Command", kVehicle, seq);
    topside.submit("once.Note", kVehicle, seq);
  }
  scheduler.run_for(900s);
  const int acks_lost = topside.ack_losing().lost;
  const uint64_t sent_while_losing = topside.queues->stats("once.Command").sent;
  topside.ack_losing().losing = false;
  scheduler.run_for(600s);

  EXPECT_GT(sent_while_losing, 2u * kEach) << "the topside did not resend while its ACKs were lost";
  EXPECT_GT(acks_lost, 20);
  EXPECT_EQ(vehicle.delivered.size(), 2u * kEach) << "not every message reached the vehicle";
  for (const auto& [message, copies] : vehicle.delivered) {
    EXPECT_EQ(copies, 1) << message << " delivered " << copies << " times";
  }
  EXPECT_GT(vehicle.queues->duplicates(), 2u * kEach);
  EXPECT_EQ(vehicle.queues->stale_refused(), 0u);
  EXPECT_EQ(topside.queues->find_queue("once.Command")->size(), 0u) << "the ACKs did not clear the topside";
  EXPECT_EQ(topside.queues->find_queue("once.Note")->size(), 0u);
  std::printf("acks lost %d; vehicle dropped %llu resends\n", acks_lost,
              static_cast<unsigned long long>(vehicle.queues->duplicates()));
}

}  // namespace
}  // namespace acomms
