// Two nodes on the simulated clock (queues, fixed TDMA, sim drivers on one
// SimChannel) where every ACK is lost for 15 minutes, three times the old
// 300 s duplicate window: the topside resends its Commands and Notes all
// that while, and when the ACKs get through at last each message must have
// reached the vehicle exactly once. Before the window followed the ttl,
// every resend after 300 s was taken as new.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "core/scheduler.h"
#include "link/link_controller.h"
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

struct Node {
  Node(int32_t id, core::SimulatedScheduler& scheduler, std::shared_ptr<drivers::SimChannel> channel,
       const std::string& proto) {
    codec.load(proto);
    v1::QueueConfig queue_config;
    // The defaults: duplicate_window_s 300, ttl_s 1800.
    pb::TextFormat::ParseFromString(
        R"(type { type: "once.Command" roles { source_field: "src" destination_field: "dest" timestamp_field: "time" } }
           type { type: "once.Note" roles { source_field: "src" destination_field: "dest" } })",
        &queue_config);
    queues = std::make_unique<queue::QueueManager>(codec, queue_config, id, scheduler.clock(), journal);

    driver_config.set_name("sim");
    driver_config.set_modem_id(static_cast<uint32_t>(id));
    driver_config.mutable_sim()->mutable_position()->set_x(id == kVehicle ? 500 : 0);
    driver = std::make_unique<drivers::SimDriver>(driver_config, scheduler, channel);
    ack_losing = std::make_unique<AckLosingDriver>(*driver);

    v1::MacConfig mac_config;
    pb::TextFormat::ParseFromString(
        R"(name: "fixed" slot { src: 1 rate: 1 seconds: 10 } slot { src: 2 rate: 1 seconds: 10 })", &mac_config);
    mac = mac::make_mac(mac_config, id, scheduler);
    link = std::make_unique<link::LinkController>(
        id, *queues, *mac, *ack_losing, [this](queue::ReceivedMessage m, const v1::ModemTransmission&) {
          const auto* seq = m.message->GetDescriptor()->FindFieldByName("seq");
          ++delivered[m.type + " " + std::to_string(m.message->GetReflection()->GetInt32(*m.message, seq))];
        });
  }

  void submit(const std::string& type, int32_t dest, int seq) {
    auto m = codec.new_message(type);
    pb::TextFormat::ParseFromString("dest: " + std::to_string(dest) + " seq: " + std::to_string(seq), m.get());
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
  std::unique_ptr<AckLosingDriver> ack_losing;
  std::unique_ptr<mac::Mac> mac;
  std::unique_ptr<link::LinkController> link;
  std::map<std::string, int> delivered;  // "type seq" -> copies
};

TEST(LostAcksNetwork, AcksLostThreeTimesTheOldWindowStillDeliverEachMessageExactlyOnce) {
  fs::path dir = fs::temp_directory_path() / ("acomms-lost-acks-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "once.proto") << kProto;

  core::SimulatedScheduler scheduler{core::Clock::time_point(std::chrono::seconds(kStart))};
  auto channel = drivers::SimChannel::create(/*seed=*/11);
  Node vehicle(kVehicle, scheduler, channel, (dir / "once.proto").string());
  Node topside(kTopside, scheduler, channel, (dir / "once.proto").string());
  topside.ack_losing->losing = true;
  vehicle.link->start();
  topside.link->start();

  constexpr int kEach = 40;
  for (int seq = 0; seq < kEach; ++seq) {
    topside.submit("once.Command", kVehicle, seq);
    topside.submit("once.Note", kVehicle, seq);
  }
  scheduler.run_for(900s);
  const int acks_lost = topside.ack_losing->lost;
  const uint64_t sent_while_losing = topside.queues->stats("once.Command").sent;
  topside.ack_losing->losing = false;
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
  fs::remove_all(dir);
}

}  // namespace
}  // namespace acomms
