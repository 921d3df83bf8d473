// The daemon's last step of a telemetry gap (node/unheard_links.h), with
// real NodeLinks on the simulated clock: two links ("acoustic", "sat") whose
// drivers are the test's (they deliver what the test says the modem heard
// and lose silently what the test does not deliver), the node's queues on
// an in-memory journal, the telemetry sequence (telemetry/sequence_gaps.h)
// and UnheardPackets over the links, wired as the Daemon wires them.
// A gap becomes exactly its missing count of packet events, less the
// losses a link recorded meanwhile, from the sender, on the link that last
// delivered a message from it, at that link's last rate, not decoded and
// without measured figures, with the model's prediction where the link has
// one (the acoustic link is a "micromodem" with driver.micromodem.prediction
// and GRAM's built-in model in free field, as in link_prediction_test.cpp;
// the satellite link has none); a late copy makes none.
#include "node/unheard_links.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

#include "acomms/v1/link_figures.pb.h"
#include "core/event_loop.h"
#include "core/scheduler.h"
#include "gram/model_engine.h"
#include "gram/model_pool.h"
#include "gram/vehicle_environment.h"
#include "link/driver.h"
#include "link/driver_registry.h"
#include "link/link_choice.h"
#include "queue/memory_journal.h"
#include "queue/queue_manager.h"
#include "telemetry/sequence_gaps.h"
#include "temp_dir.h"
#include "free_field_environment.h"

namespace acomms::node {
namespace {

constexpr int32_t kOwn = 1, kSender = 2;

// Free field (free_field_environment.h): TL is 20 log10(r).
constexpr const char* kFreeField = acomms::test::kFreeFieldEnvironment;
constexpr const char* kPrediction =
    "micromodem { prediction { source_level_db: 190 noise_level_db: 85 max_range_m: 1000 range_step_m: 10"
    " fixed { modem: 1 position { x: 300 y: 0 z: -10 } } fixed { modem: 2 position { x: 0 y: 0 z: -10 } } } }";

constexpr const char* kStatusProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package net;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 10 max_bytes: 32 };
  required int32 src = 1 [(dccl.field) = { min: 0 max: 127 }];
  required int32 dest = 2 [(dccl.field) = { min: 0 max: 127 }];
  required int32 battery = 3 [(dccl.field) = { min: 0 max: 100 }];
}
)";

// A modem the test speaks for: what it "hears" goes to the link as is.
class TestModem final : public link::Driver {
 public:
  explicit TestModem(std::vector<TestModem*>& started) : started_(started) {}
  void start(link::DriverCallbacks callbacks) override {
    callbacks_ = std::move(callbacks);
    started_.push_back(this);
  }
  void stop() override {}
  void do_work() override {}
  void initiate_transmission(const v1::ModemTransmission&) override {}
  link::DriverCallbacks callbacks_;

 private:
  std::vector<TestModem*>& started_;
};

class UnheardLinks : public ::testing::Test {
 protected:
  UnheardLinks() {
    gram::Environment base;
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(kFreeField, &base));
    environment_ = std::make_unique<gram::VehicleEnvironment>(base, gram::VehicleEnvironmentOptions{});
    pool_ = std::make_unique<gram::ModelPool>(gram::ModelPoolOptions{1, 16, 1 << 20}, gram::make_builtin_engine());
    std::ofstream(dir_.path() / "status.proto") << kStatusProto;
    codec_.load((dir_.path() / "status.proto").string());
    v1::QueueConfig queue_config;
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(
        R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } })", &queue_config));
    queues_ = std::make_unique<queue::QueueManager>(codec_, queue_config, kOwn, scheduler_.clock(), journal_);
    queues_->restore();
    std::vector<v1::LinkConfig> configs(2);
    const char* cycle = R"(mac { name: "fixed" slot { src: 1 rate: 0 seconds: 10 } slot { src: 2 rate: 0 seconds: 10 } })";
    for (int i = 0; i < 2; ++i) {
      EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(cycle, &configs[i]));
      configs[i].set_name(i == 0 ? "acoustic" : "sat");
      if (i == 0) EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(kPrediction, configs[i].mutable_driver()));
      configs[i].mutable_driver()->set_name(i == 0 ? "micromodem" : "test");
      configs[i].mutable_driver()->set_modem_id(kOwn);
    }
    choice_ = std::make_unique<link::LinkChoice>(
        link::LinkChoice::from_config(configs, queue_config, scheduler_.clock().now_seconds()));
    for (const char* name : {"test", "micromodem"}) {
      drivers_.add(name, [this](const link::DriverContext&) { return std::make_unique<TestModem>(modems_); });
    }
    parts_ = std::make_unique<LinkParts>(LinkParts{
        .own_id = kOwn,
        .data_dir = dir_.path().string(),
        .link_count = 2,
        .scheduler = scheduler_,
        .core = core_,
        .drivers = drivers_,
        .node_position = node_position_,
        .models = pool_.get(),
        .queues = *queues_,
        .choice = *choice_,
        .deliver = [this](queue::ReceivedMessage, const v1::ModemTransmission&) { ++delivered_; },
        .after_receipt_durable = [](std::function<void()> then) { then(); },
        .modem_positions = &modem_positions_,
        .environment = environment_.get(),
    });
    for (int i = 0; i < 2; ++i) links_.push_back(std::make_unique<NodeLink>(configs[i], i, *parts_));
    for (auto& link : links_) {
      link->controller().start();
      scheduler_.run_for(std::chrono::milliseconds(1));  // the supervisor starts its driver
    }
    unheard_ = std::make_unique<UnheardPackets>(unheard_on_links(links_));
  }
  ~UnheardLinks() override {
    for (auto& link : links_) link->controller().stop();
  }

  // Link `index` delivers a Status from the sender, heard at `rate`.
  void hear(int index, int32_t rate) {
    ASSERT_EQ(modems_.size(), 2u);
    auto status = codec_.new_message("net.Status");
    ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(
        "src: 2 dest: 1 battery: " + std::to_string(++battery_), status.get()));
    v1::ModemTransmission t;
    t.set_type(v1::ModemTransmission::DATA);
    t.set_src(kSender);
    t.set_dest(kOwn);
    t.set_rate(rate);
    t.add_frame(codec_.encode(*status));
    const int before = delivered_;
    modems_[index]->callbacks_.on_receive(t);
    ASSERT_EQ(delivered_, before + 1);
    scheduler_.run_for(std::chrono::seconds(5));
  }
  // Link `index`'s modem heard a packet from the sender and could not decode it.
  void damaged(int index) {
    v1::ModemTransmission t;
    t.set_type(v1::ModemTransmission::DATA);
    t.set_src(kSender);
    t.set_dest(kOwn);
    t.set_rate(3);
    modems_[index]->callbacks_.on_reception_failed(t);
  }
  // The sender's telemetry message `sequence` arrived (as TelemetryNode
  // tells the Daemon).
  void telemetry(uint32_t sequence) { unheard_->on_sequence(kSender, gaps_.observe(kSender, sequence, false), false); }
  // Runs what was posted to the core (the model's grid) on this thread
  // until `done`, 60 s at most.
  template <typename F>
  bool run_core_until(F done) {
    for (int i = 0; i < 6000 && !done(); ++i) {
      core_.context().restart();
      if (core_.context().poll() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return done();
  }
  // Packet events recorded since event `from`, not decoded.
  std::vector<v1::LinkFigures> lost_since(size_t from) const {
    std::vector<v1::LinkFigures> lost;
    std::vector<queue::QueueEvent> events = journal_.events();
    for (size_t i = from; i < events.size(); ++i) {
      if (events[i].kind != queue::QueueEventKind::kPacket) continue;
      v1::LinkFigures f;
      EXPECT_TRUE(f.ParseFromString(events[i].link_figures.value_or("")));
      if (!f.decoded()) lost.push_back(f);
    }
    return lost;
  }

  testing::TempDir dir_{"acomms-unheard"};
  core::SimulatedScheduler scheduler_{core::Clock::time_point(std::chrono::seconds(1'748'772'000))};
  core::EventLoop core_;
  dccl::Codec codec_;
  queue::MemoryJournal journal_;
  std::unique_ptr<queue::QueueManager> queues_;
  std::unique_ptr<link::LinkChoice> choice_;
  link::DriverRegistry drivers_;
  core::NodePosition node_position_;
  ModemPositions modem_positions_;
  std::unique_ptr<gram::VehicleEnvironment> environment_;
  std::unique_ptr<gram::ModelPool> pool_;
  std::vector<TestModem*> modems_;
  std::unique_ptr<LinkParts> parts_;
  std::vector<std::unique_ptr<NodeLink>> links_;
  std::unique_ptr<UnheardPackets> unheard_;
  telemetry::SequenceGaps gaps_;
  int delivered_ = 0;
  int battery_ = 0;
};

TEST_F(UnheardLinks, AGapIsLostPacketsOnTheLinkThatLastHeardTheSenderLessWhatItRecorded) {
  hear(1, 1);  // the satellite link heard it first, at rate 1
  // More than kSeveralLinks_s later (else its messages could be in flight
  // on either link, and no gap is counted: below) ...
  scheduler_.run_for(std::chrono::seconds(static_cast<int>(UnheardPackets::kSeveralLinks_s) + 100));
  hear(0, 3);  // ... the acoustic link, at rate 3: the newest
  telemetry(1);
  damaged(0);  // one of the missing packets the acoustic link saw, damaged
  // Its event asked the acoustic link's model for its grid: wait for it.
  ASSERT_NE(links_[0]->prediction(), nullptr);
  ASSERT_TRUE(run_core_until([&] { return links_[0]->prediction()->counters().grids == 1; }));
  size_t mark = journal_.events().size();
  hear(0, 3);
  telemetry(5);  // 2, 3 and 4 missing: one the link recorded, two only the gap tells of
  std::vector<v1::LinkFigures> lost = lost_since(mark);
  ASSERT_EQ(lost.size(), 2u);
  for (const v1::LinkFigures& f : lost) {
    EXPECT_EQ(f.transmission_src(), kSender);
    EXPECT_EQ(f.link(), "acoustic");
    EXPECT_EQ(f.rate(), 3);
    EXPECT_FALSE(f.has_snr_in_db()) << "nothing was measured";
    ASSERT_TRUE(f.has_predicted_snr_db()) << "the acoustic link's model";
    EXPECT_NEAR(f.predicted_tl_db(), 20 * std::log10(300.0), 1.0);
    EXPECT_NEAR(f.predicted_snr_db(), 190 - f.predicted_tl_db() - 85, 1e-9);
  }
  EXPECT_EQ(unheard_->counters().recorded, 2u);
  EXPECT_EQ(unheard_->counters().link_recorded, 1u);

  mark = journal_.events().size();
  telemetry(3);  // a late copy: nothing is missing
  EXPECT_TRUE(lost_since(mark).empty());

  // The satellite link hears it too, within the hour: a gap now may be
  // messages still in flight on the other link, so none is counted.
  hear(1, 1);
  mark = journal_.events().size();
  telemetry(7);  // 6 missing
  EXPECT_TRUE(lost_since(mark).empty());
  EXPECT_EQ(unheard_->counters().recorded, 2u);

  // Over an hour later only the satellite link hears it: the gap is its.
  scheduler_.run_for(std::chrono::seconds(static_cast<int>(UnheardPackets::kSeveralLinks_s) + 100));
  hear(1, 1);
  mark = journal_.events().size();
  telemetry(9);  // 8 missing
  lost = lost_since(mark);
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_EQ(lost[0].link(), "sat");
  EXPECT_EQ(lost[0].rate(), 1);
  EXPECT_FALSE(lost[0].has_predicted_snr_db()) << "no model on the satellite link";
  EXPECT_FALSE(lost[0].has_snr_in_db());
  EXPECT_EQ(unheard_->counters().recorded, 3u);
}

}  // namespace
}  // namespace acomms::node
