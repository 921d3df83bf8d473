#pragma once
// Keeps one Driver running for the daemon.
//
// A modem driver fails in ordinary ways (the serial adapter is unplugged,
// the modem reboots, a peer's host disappears). None of that may take the
// daemon down: the queues keep their messages and the link comes back.
// The supervisor builds and starts the driver, calls do_work() a few times
// a second on the Scheduler, and when start(), do_work() or
// initiate_transmission() throws it logs the error, stops the driver, and
// builds and starts a fresh one after a backoff (restart_min_s doubling up
// to restart_max_s). A transmission the MAC asks for while the driver is
// down is reported failed at once (on_transmit_result ok=false): the MAC
// and queues must know the slot was lost rather than wait for it.
//
// It is itself a Driver, so whatever drives a Driver (the LinkController)
// can be given the supervisor instead and gain the restarts for free.
// Everything runs on the core thread (the Scheduler's).

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "acomms/v1/config.pb.h"
#include "core/scheduler.h"
#include "link/backoff.h"
#include "link/driver.h"

namespace acomms::link {

struct SupervisorOptions {
  std::string driver_name = "driver";  // for logs and status
  double restart_min_s = 1;
  double restart_max_s = 60;
  std::chrono::milliseconds work_interval{200};

  // From the config's driver section (0 means the defaults above).
  static SupervisorOptions from_config(const v1::DriverConfig& config);
};

enum class DriverState {
  kStopped,     // not started, or stopped by the owner
  kRunning,     // started and working
  kRestarting,  // failed; a restart is scheduled at restart_at
};

const char* to_string(DriverState state);

// What the supervisor knows, for logs and a LinkStatus API.
struct DriverStatus {
  std::string driver;
  DriverState state = DriverState::kStopped;
  std::string last_error;                     // why it last failed ("" if never)
  core::Clock::time_point since;              // when the state was entered
  core::Clock::time_point restart_at;         // kRestarting: when it is tried again
  uint32_t consecutive_failures = 0;          // since it last ran long enough
  uint64_t failures = 0;                      // in total
  uint64_t starts = 0;                        // successful starts in total
};

// "running", "failed: <reason>; restarting in 4 s", "stopped".
std::string describe(const DriverStatus& status, core::Clock::time_point now);

class DriverSupervisor final : public Driver {
 public:
  // Builds a fresh driver for each (re)start; may throw like a driver's start.
  using Factory = std::function<std::unique_ptr<Driver>()>;
  using StatusCallback = std::function<void(const DriverStatus&)>;

  DriverSupervisor(Factory factory, core::Scheduler& scheduler, SupervisorOptions options = {});
  ~DriverSupervisor() override;
  DriverSupervisor(const DriverSupervisor&) = delete;
  DriverSupervisor& operator=(const DriverSupervisor&) = delete;

  // Every state change (running, restarting, stopped), e.g. for LinkStatus.
  void set_status_callback(StatusCallback on_status) { on_status_ = std::move(on_status); }

  // Starts the driver (or schedules its restart if that fails); never
  // throws for a driver failure.
  void start(DriverCallbacks callbacks) override;
  // Stops the driver and any pending restart; no driver callback runs after it.
  void stop() override;
  // Nothing: the supervisor calls the driver's do_work on the Scheduler.
  void do_work() override {}
  // Hands the transmission to the driver, or reports it failed if the
  // driver is down (or fails on it).
  void initiate_transmission(const v1::ModemTransmission& transmission) override;
  // The running driver's timing (the defaults while it is down).
  std::chrono::nanoseconds packet_air_time(int32_t rate, uint32_t num_frames) const override;
  std::chrono::nanoseconds ack_time(int32_t rate) const override;
  double sound_speed() const override;
  // Every driver's counters since the supervisor was built, across restarts.
  DriverCounters counters() const override;
  // The running driver's, its errors naming it ("driver sim does not
  // support ..."); kUnavailable while it is down.
  DriverSpecificResult check_driver_specific(const v1::ModemTransmission& request) const override;
  void send_driver_specific(const v1::ModemTransmission& request, double deadline_s,
                            DriverSpecificDone done) override;
  // The running driver's (nothing while it is down).
  std::string modem() const override { return driver_ ? driver_->modem() : ""; }
  bool acks_in_hardware() const override { return driver_ && driver_->acks_in_hardware(); }

  const DriverStatus& status() const { return status_; }
  // The running driver, or nullptr while it is down (for tests and tools).
  Driver* driver() { return driver_.get(); }

 private:
  void try_start();
  void work();
  void fail(const std::string& reason);
  void set_state(DriverState state);
  void schedule_work();

  Factory factory_;
  core::Scheduler& scheduler_;
  SupervisorOptions options_;
  Backoff backoff_;
  DriverCallbacks callbacks_;
  StatusCallback on_status_;
  std::unique_ptr<Driver> driver_;
  DriverCounters carried_;  // from the drivers that failed or were stopped
  DriverStatus status_;
  core::Scheduler::TaskId work_task_ = 0;
  core::Scheduler::TaskId restart_task_ = 0;
};

}  // namespace acomms::link
