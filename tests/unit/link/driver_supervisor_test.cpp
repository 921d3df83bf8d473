#include "link/driver_supervisor.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/scheduler.h"

namespace acomms::link {
namespace {

using core::Clock;
using std::chrono::milliseconds;
using std::chrono::seconds;

// What the fake drivers do, shared by every instance the factory builds.
struct Script {
  bool fail_start = false;
  bool fail_work = false;
  bool fail_transmit = false;
  bool throw_other = false;  // a non-DriverError exception (a driver bug)
  int built = 0, starts = 0, stops = 0, works = 0;
  DriverCounters lost_by_each;  // what every driver built reports
  std::vector<v1::ModemTransmission> transmitted;
};

class FakeDriver final : public Driver {
 public:
  explicit FakeDriver(Script& script) : script_(script) { ++script_.built; }
  void start(DriverCallbacks) override {
    ++script_.starts;
    if (script_.throw_other) throw std::logic_error("driver bug");
    if (script_.fail_start) throw DriverError("cannot open /dev/ttyFAKE: No such file or directory");
  }
  void stop() override { ++script_.stops; }
  void do_work() override {
    ++script_.works;
    if (script_.fail_work) throw DriverError("/dev/ttyFAKE: read failed: Input/output error");
  }
  void initiate_transmission(const v1::ModemTransmission& tx) override {
    if (script_.fail_transmit) throw DriverError("/dev/ttyFAKE: write failed");
    script_.transmitted.push_back(tx);
  }
  std::chrono::nanoseconds packet_air_time(int32_t, uint32_t num_frames) const override {
    return milliseconds(100) * num_frames;
  }
  DriverCounters counters() const override { return script_.lost_by_each; }

 private:
  Script& script_;
};

class DriverSupervisorTest : public ::testing::Test {
 protected:
  DriverSupervisorTest() : t0_(Clock::time_point(seconds(1'700'000'000))), scheduler_(t0_) {}

  std::unique_ptr<DriverSupervisor> make(double min_s, double max_s) {
    SupervisorOptions options;
    options.driver_name = "fake";
    options.restart_min_s = min_s;
    options.restart_max_s = max_s;
    options.work_interval = milliseconds(100);
    auto supervisor = std::make_unique<DriverSupervisor>(
        [this] { return std::make_unique<FakeDriver>(script_); }, scheduler_, options);
    DriverCallbacks callbacks;
    callbacks.on_transmit_result = [this](const v1::ModemTransmission& tx, bool ok, const std::string& error) {
      results_.push_back({tx, ok, error});
    };
    supervisor->set_status_callback([this](const DriverStatus& status) { states_.push_back(status.state); });
    supervisor->start(callbacks);
    return supervisor;
  }

  struct Result {
    v1::ModemTransmission tx;
    bool ok;
    std::string error;
  };
  Clock::time_point t0_;
  core::SimulatedScheduler scheduler_;
  Script script_;
  std::vector<Result> results_;
  std::vector<DriverState> states_;
};

TEST_F(DriverSupervisorTest, RunsAndCallsDoWorkPeriodically) {
  auto supervisor = make(1, 60);
  EXPECT_EQ(supervisor->status().state, DriverState::kRunning);
  scheduler_.run_until(t0_ + seconds(1));
  EXPECT_EQ(script_.works, 10);
  v1::ModemTransmission tx;
  tx.set_src(1);
  supervisor->initiate_transmission(tx);
  EXPECT_EQ(script_.transmitted.size(), 1u);
  supervisor->stop();
  EXPECT_EQ(script_.stops, 1);
  EXPECT_EQ(supervisor->status().state, DriverState::kStopped);
  scheduler_.run_until(t0_ + seconds(2));
  EXPECT_EQ(script_.works, 10);  // no work after stop
}

TEST_F(DriverSupervisorTest, FailedStartIsRetriedWithDoublingBackoffUpToMax) {
  script_.fail_start = true;
  auto supervisor = make(1, 8);
  const auto& status = supervisor->status();
  EXPECT_EQ(status.state, DriverState::kRestarting);
  EXPECT_NE(status.last_error.find("/dev/ttyFAKE"), std::string::npos);
  EXPECT_EQ(status.restart_at, t0_ + seconds(1));
  EXPECT_EQ(describe(status, t0_), "failed: " + status.last_error + "; restarting in 1.0 s");

  // Attempts at 1, 1+2, 3+4, 7+8, 15+8 s: the delay doubles, then stays at max.
  const int attempts_at[] = {1, 3, 7, 15, 23};
  int starts = 1;
  for (int at : attempts_at) {
    scheduler_.run_until(t0_ + seconds(at) - milliseconds(1));
    EXPECT_EQ(script_.starts, starts) << "before " << at << " s";
    scheduler_.run_until(t0_ + seconds(at));
    EXPECT_EQ(script_.starts, ++starts) << "at " << at << " s";
  }
  EXPECT_EQ(status.restart_at, t0_ + seconds(31));
  EXPECT_EQ(status.failures, 6u);
  EXPECT_EQ(script_.stops, 6);  // each failed driver was stopped

  // The device comes back: the next attempt runs it.
  script_.fail_start = false;
  scheduler_.run_until(t0_ + seconds(31));
  EXPECT_EQ(status.state, DriverState::kRunning);
  EXPECT_EQ(status.starts, 1u);
  EXPECT_EQ(script_.built, 7);  // a fresh driver for each attempt
}

TEST_F(DriverSupervisorTest, DoWorkFailureStopsAndRestartsTheDriver) {
  auto supervisor = make(2, 60);
  scheduler_.run_until(t0_ + milliseconds(500));
  script_.fail_work = true;
  scheduler_.run_until(t0_ + milliseconds(600));
  EXPECT_EQ(supervisor->status().state, DriverState::kRestarting);
  EXPECT_EQ(supervisor->status().restart_at, t0_ + milliseconds(2600));
  EXPECT_EQ(supervisor->driver(), nullptr);
  EXPECT_EQ(script_.stops, 1);
  script_.fail_work = false;
  scheduler_.run_until(t0_ + milliseconds(2600));
  EXPECT_EQ(supervisor->status().state, DriverState::kRunning);
  EXPECT_EQ(states_, (std::vector<DriverState>{DriverState::kRunning, DriverState::kRestarting,
                                               DriverState::kRunning}));
}

TEST_F(DriverSupervisorTest, CountersAddUpAcrossRestarts) {
  script_.lost_by_each = {3, 1};
  auto supervisor = make(2, 60);
  EXPECT_EQ(supervisor->counters().lost_half_duplex, 3u);
  EXPECT_EQ(supervisor->counters().lost_collision, 1u);
  script_.fail_work = true;
  scheduler_.run_until(t0_ + milliseconds(150));
  ASSERT_EQ(supervisor->driver(), nullptr);
  // Down: what the failed driver counted is kept.
  EXPECT_EQ(supervisor->counters().lost_half_duplex, 3u);
  script_.fail_work = false;
  scheduler_.run_until(t0_ + milliseconds(2200));
  ASSERT_NE(supervisor->driver(), nullptr);
  // The new driver's own count comes on top.
  EXPECT_EQ(supervisor->counters().lost_half_duplex, 6u);
  EXPECT_EQ(supervisor->counters().lost_collision, 2u);
}

TEST_F(DriverSupervisorTest, TimingIsTheRunningDriversOrTheDefaultsWhileDown) {
  auto supervisor = make(2, 60);
  EXPECT_EQ(supervisor->packet_air_time(5, 3), milliseconds(300));
  script_.fail_work = true;
  scheduler_.run_until(t0_ + milliseconds(150));
  ASSERT_EQ(supervisor->driver(), nullptr);
  // The defaults: the rate table (0.3 s + 3 x 2048 bits / 5300 bps) + 10 %.
  EXPECT_NEAR(std::chrono::duration<double>(supervisor->packet_air_time(5, 3)).count(),
              (0.3 + 3 * 2048.0 / 5300) * 1.1, 1e-6);
}

TEST_F(DriverSupervisorTest, TransmissionWhileDownIsReportedFailed) {
  script_.fail_start = true;
  auto supervisor = make(1, 60);
  v1::ModemTransmission tx;
  tx.set_src(1);
  tx.set_dest(2);
  supervisor->initiate_transmission(tx);
  ASSERT_EQ(results_.size(), 1u);
  EXPECT_FALSE(results_[0].ok);
  EXPECT_EQ(results_[0].tx.dest(), 2);
  EXPECT_NE(results_[0].error.find("driver fake is failed: cannot open /dev/ttyFAKE"), std::string::npos)
      << results_[0].error;
  EXPECT_NE(results_[0].error.find("restarting in 1.0 s"), std::string::npos) << results_[0].error;
  EXPECT_TRUE(script_.transmitted.empty());
}

TEST_F(DriverSupervisorTest, TransmissionThatThrowsIsReportedFailedAndRestarts) {
  auto supervisor = make(1, 60);
  script_.fail_transmit = true;
  v1::ModemTransmission tx;
  supervisor->initiate_transmission(tx);
  ASSERT_EQ(results_.size(), 1u);
  EXPECT_FALSE(results_[0].ok);
  EXPECT_NE(results_[0].error.find("write failed"), std::string::npos);
  EXPECT_EQ(supervisor->status().state, DriverState::kRestarting);
}

TEST_F(DriverSupervisorTest, AnyExceptionIsContainedNotJustDriverError) {
  script_.throw_other = true;
  auto supervisor = make(1, 60);
  EXPECT_EQ(supervisor->status().state, DriverState::kRestarting);
  EXPECT_EQ(supervisor->status().last_error, "driver bug");
}

TEST_F(DriverSupervisorTest, BackoffResetsAfterTheDriverRanLongEnough) {
  script_.fail_start = true;
  auto supervisor = make(1, 4);
  scheduler_.run_until(t0_ + seconds(1));  // second failure: next delay 2 s
  EXPECT_EQ(supervisor->status().restart_at, t0_ + seconds(3));
  script_.fail_start = false;
  scheduler_.run_until(t0_ + seconds(3));
  ASSERT_EQ(supervisor->status().state, DriverState::kRunning);
  scheduler_.run_until(t0_ + seconds(8));  // ran 5 s >= max (4 s)
  script_.fail_work = true;
  scheduler_.run_until(t0_ + seconds(8) + milliseconds(100));
  EXPECT_EQ(supervisor->status().state, DriverState::kRestarting);
  EXPECT_EQ(supervisor->status().restart_at - scheduler_.clock().now(), seconds(1));
}

TEST_F(DriverSupervisorTest, IsADriverItselfSoItCanStandInForOne) {
  auto supervisor = make(1, 60);
  Driver& driver = *supervisor;  // e.g. handed to the LinkController
  driver.do_work();               // a no-op: the supervisor keeps its own schedule
  v1::ModemTransmission tx;
  driver.initiate_transmission(tx);
  EXPECT_EQ(script_.transmitted.size(), 1u);
  driver.stop();
  EXPECT_EQ(states_.back(), DriverState::kStopped);
  driver.start({});
  EXPECT_EQ(supervisor->status().state, DriverState::kRunning);
}

TEST_F(DriverSupervisorTest, OptionsFromConfigUseDefaultsForZero) {
  v1::DriverConfig config;
  config.set_name("udp");
  auto options = SupervisorOptions::from_config(config);
  EXPECT_EQ(options.driver_name, "udp");
  EXPECT_EQ(options.restart_min_s, 1);
  EXPECT_EQ(options.restart_max_s, 60);
  config.set_restart_min_s(0.5);
  config.set_restart_max_s(10);
  options = SupervisorOptions::from_config(config);
  EXPECT_EQ(options.restart_min_s, 0.5);
  EXPECT_EQ(options.restart_max_s, 10);
}

}  // namespace
}  // namespace acomms::link
