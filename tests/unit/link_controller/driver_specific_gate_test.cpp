// The slot rule for driver-specific transmissions (link/driver_specific_gate.h),
// through the LinkController on simulated time: a request waits for this
// node's slot (its wait counted against its deadline), a slotless node's
// request goes when a poll gives it the channel, and the driver's refusals
// come back at once.

#include <gtest/gtest.h>

#include <optional>

#include "core/scheduler.h"
#include "link/link_controller.h"
#include "queue/memory_journal.h"

namespace acomms::link {
namespace {

using namespace std::chrono_literals;
constexpr double kStart = 1'700'000'000;

// Records what reaches it; answers a driver-specific request `answer_after` later.
class ExtraDriver final : public Driver {
 public:
  explicit ExtraDriver(core::Scheduler& scheduler) : scheduler_(scheduler) {}
  void start(DriverCallbacks callbacks) override { callbacks_ = std::move(callbacks); }
  void stop() override {}
  void do_work() override {}
  void initiate_transmission(const v1::ModemTransmission& t) override { initiated.push_back(t); }
  DriverSpecificResult check_driver_specific(const v1::ModemTransmission& r) const override {
    if (r.dest() == 99) return driver_specific_error(DriverSpecificStatus::kInvalidArgument, "dest 99 is not a modem", r);
    return {DriverSpecificStatus::kOk, "", r};
  }
  void send_driver_specific(const v1::ModemTransmission& r, double deadline_s, DriverSpecificDone done) override {
    sent_at.push_back(scheduler_.clock().now_seconds() - kStart);
    deadlines.push_back(deadline_s - kStart);
    scheduler_.after(answer_after, [r, done] { done({DriverSpecificStatus::kOk, "", r}); });
  }
  // A poll for us heard: the driver asks for our data (not in our slot).
  v1::ModemTransmission answer_poll() {
    v1::ModemTransmission out;
    out.set_src(1);
    out.set_dest(3);
    out.set_max_frame_bytes(32);
    out.set_max_num_frames(3);
    callbacks_.on_data_request(&out);
    return out;
  }
  void report(const v1::ModemTransmission& t) { callbacks_.on_transmit_result(t, true, ""); }

  core::Scheduler& scheduler_;
  DriverCallbacks callbacks_;
  std::vector<v1::ModemTransmission> initiated;
  std::vector<double> sent_at, deadlines;
  std::chrono::milliseconds answer_after{500};
};

class SlotMac final : public mac::Mac {
 public:
  void start(Transmit transmit) override { transmit_ = std::move(transmit); }
  void stop() override {}
  void set_cycle(const mac::Cycle&) override {}
  const mac::Cycle& cycle() const override { return cycle_; }
  void on_receive(const v1::ModemTransmission&) override {}
  void slot(int32_t src) {
    v1::ModemTransmission t;
    t.set_src(src);
    transmit_(t);
  }
  Transmit transmit_;
  mac::Cycle cycle_;
};

class DriverSpecificGateTest : public ::testing::Test {
 protected:
  void SetUp() override {
    queues_ = std::make_unique<queue::QueueManager>(codec_, v1::QueueConfig(), 1, scheduler_.clock(), journal_);
    LinkOptions options;
    options.clock = &scheduler_.clock();
    options.scheduler = &scheduler_;
    link_ = std::make_unique<LinkController>(1, *queues_, mac_, driver_,
                                             [](queue::ReceivedMessage, const v1::ModemTransmission&) {}, options);
    link_->start();
  }
  void request(double timeout_s, int32_t dest = 2) {
    v1::ModemTransmission r;
    r.set_type(v1::ModemTransmission::DRIVER_SPECIFIC);
    r.set_dest(dest);
    link_->request_driver_specific(r, timeout_s, [this](DriverSpecificResult result) { result_ = std::move(result); });
  }
  double now() const { return scheduler_.clock().now_seconds() - kStart; }

  core::SimulatedScheduler scheduler_{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
  dccl::Codec codec_;
  queue::MemoryJournal journal_;
  std::unique_ptr<queue::QueueManager> queues_;
  ExtraDriver driver_{scheduler_};
  SlotMac mac_;
  std::unique_ptr<LinkController> link_;
  std::optional<DriverSpecificResult> result_;
};

TEST_F(DriverSpecificGateTest, ARequestOutsideTheSlotWaitsForThisNodesSlotAndTheWaitIsReported) {
  request(30);
  scheduler_.run_for(3s);
  mac_.slot(2);  // another node's slot: nothing of ours goes out
  EXPECT_TRUE(driver_.sent_at.empty());
  EXPECT_EQ(driver_.initiated.size(), 1u);
  scheduler_.run_for(4s);
  mac_.slot(1);  // ours: the extra instead of data
  ASSERT_EQ(driver_.sent_at.size(), 1u);
  EXPECT_DOUBLE_EQ(driver_.sent_at[0], 7);
  EXPECT_DOUBLE_EQ(driver_.deadlines[0], 30);  // what is left of the deadline goes to the driver
  EXPECT_EQ(driver_.initiated.size(), 1u);     // the slot carried no data
  EXPECT_FALSE(result_.has_value());
  scheduler_.run_for(1s);
  ASSERT_TRUE(result_.has_value());
  EXPECT_EQ(result_->status, DriverSpecificStatus::kOk);
  EXPECT_DOUBLE_EQ(result_->waited_s, 7);
  mac_.slot(1);  // the next slot is data again
  EXPECT_EQ(driver_.initiated.size(), 2u);
}

TEST_F(DriverSpecificGateTest, ADeadlineThatPassesBeforeTheSlotFailsWithoutSending) {
  request(5);
  scheduler_.run_for(4900ms);
  EXPECT_FALSE(result_.has_value());
  scheduler_.run_for(200ms);
  ASSERT_TRUE(result_.has_value());
  EXPECT_EQ(result_->status, DriverSpecificStatus::kDeadlineExceeded);
  EXPECT_NE(result_->error.find("waiting for this node's slot"), std::string::npos) << result_->error;
  mac_.slot(1);
  EXPECT_TRUE(driver_.sent_at.empty());
  EXPECT_EQ(driver_.initiated.size(), 1u);
}

TEST_F(DriverSpecificGateTest, ASlotlessNodeSendsWhenAPollGivesItTheChannel) {
  request(60);
  scheduler_.run_for(2s);
  v1::ModemTransmission answer = driver_.answer_poll();
  // The poll is answered with one blank frame, to broadcast, unacked ...
  ASSERT_EQ(answer.frame_size(), 1);
  EXPECT_EQ(answer.frame(0), "");
  EXPECT_FALSE(answer.ack_requested());
  EXPECT_TRUE(driver_.sent_at.empty());
  scheduler_.run_for(1s);
  // ... and the extra follows once that answer has gone.
  driver_.report(answer);
  // Not while the answer may still be heard at the poller: the sound's
  // travel to max_range_m (2000 m at 1500 m/s) and an ACK's time
  // (0.5 s turnaround + a 0.7 s mini-packet, plus 10 %) go first.
  double clear = 2000.0 / 1500 + 1.2 * 1.1;
  scheduler_.run_for(std::chrono::milliseconds(static_cast<int>(clear * 1000) - 10));
  EXPECT_TRUE(driver_.sent_at.empty());
  scheduler_.run_for(20ms);
  ASSERT_EQ(driver_.sent_at.size(), 1u);
  EXPECT_NEAR(driver_.sent_at[0], 3 + clear, 0.001);
}

TEST_F(DriverSpecificGateTest, TheDriversRefusalComesAtOnceWithoutWaiting) {
  request(60, 99);
  ASSERT_TRUE(result_.has_value());
  EXPECT_EQ(result_->status, DriverSpecificStatus::kInvalidArgument);
  EXPECT_EQ(result_->error, "dest 99 is not a modem");
  mac_.slot(1);
  EXPECT_TRUE(driver_.sent_at.empty());
}

TEST_F(DriverSpecificGateTest, ADriverWithoutExtrasIsUnimplementedNamingTheRequest) {
  struct Plain final : Driver {
    void start(DriverCallbacks) override {}
    void stop() override {}
    void do_work() override {}
    void initiate_transmission(const v1::ModemTransmission&) override {}
  } plain;
  v1::ModemTransmission r;
  r.set_type(v1::ModemTransmission::DRIVER_SPECIFIC);
  r.mutable_unknown_fields()->AddVarint(1100, 1);
  DriverSpecificResult result = plain.check_driver_specific(r);
  EXPECT_EQ(result.status, DriverSpecificStatus::kUnimplemented);
  EXPECT_NE(result.error.find("extension 1100"), std::string::npos) << result.error;
}

TEST_F(DriverSpecificGateTest, StoppingTheLinkFailsWhatWaits) {
  request(60);
  link_->stop();
  ASSERT_TRUE(result_.has_value());
  EXPECT_EQ(result_->status, DriverSpecificStatus::kUnavailable);
}

}  // namespace
}  // namespace acomms::link
