#include "link/driver_supervisor.h"

#include <spdlog/spdlog.h>

#include <cstdio>

#include "core/core_thread.h"

namespace acomms::link {

SupervisorOptions SupervisorOptions::from_config(const v1::DriverConfig& config) {
  SupervisorOptions options;
  options.driver_name = config.name().empty() ? "driver" : config.name();
  if (config.restart_min_s() > 0) options.restart_min_s = config.restart_min_s();
  if (config.restart_max_s() > 0) options.restart_max_s = config.restart_max_s();
  return options;
}

const char* to_string(DriverState state) {
  switch (state) {
    case DriverState::kStopped: return "stopped";
    case DriverState::kRunning: return "running";
    case DriverState::kRestarting: return "restarting";
  }
  return "unknown";
}

std::string describe(const DriverStatus& status, core::Clock::time_point now) {
  switch (status.state) {
    case DriverState::kStopped: return "stopped";
    case DriverState::kRunning: return "running";
    case DriverState::kRestarting: {
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%.1f",
                    std::chrono::duration<double>(status.restart_at - now).count());
      return "failed: " + status.last_error + "; restarting in " + seconds + " s";
    }
  }
  return "unknown";
}

DriverSupervisor::DriverSupervisor(Factory factory, core::Scheduler& scheduler, SupervisorOptions options)
    : factory_(std::move(factory)), scheduler_(scheduler), options_(std::move(options)),
      backoff_(options_.restart_min_s, options_.restart_max_s) {
  status_.driver = options_.driver_name;
}

DriverSupervisor::~DriverSupervisor() {
  on_status_ = nullptr;  // the owner is going away: tell it nothing more
  stop();
}

void DriverSupervisor::start(DriverCallbacks callbacks) {
  ACOMMS_ASSERT_CORE_THREAD();
  stop();
  callbacks_ = std::move(callbacks);
  backoff_.reset();
  status_.consecutive_failures = 0;
  try_start();
}

void DriverSupervisor::stop() {
  ACOMMS_ASSERT_CORE_THREAD();
  scheduler_.cancel(work_task_);
  scheduler_.cancel(restart_task_);
  work_task_ = restart_task_ = 0;
  if (driver_) {
    try {
      driver_->stop();
    } catch (const std::exception& e) {
      spdlog::warn("driver {}: error while stopping: {}", options_.driver_name, e.what());
    }
    carried_ += driver_->counters();  // a restarted driver counts from zero
    driver_.reset();
  }
  if (status_.state != DriverState::kStopped) set_state(DriverState::kStopped);
}

void DriverSupervisor::try_start() {
  restart_task_ = 0;
  try {
    auto driver = factory_();
    if (!driver) throw DriverError("the driver factory built nothing");
    driver_ = std::move(driver);
    driver_->start(callbacks_);
  } catch (const std::exception& e) {
    // DriverError is the expected kind; anything else is a driver bug, but
    // the daemon still must not go down for it.
    fail(e.what());
    return;
  }
  ++status_.starts;
  spdlog::info("driver {}: running", options_.driver_name);
  set_state(DriverState::kRunning);
  schedule_work();
}

void DriverSupervisor::schedule_work() {
  work_task_ = scheduler_.after(options_.work_interval, [this] {
    work_task_ = 0;
    work();
  });
}

void DriverSupervisor::work() {
  ACOMMS_ASSERT_CORE_THREAD();
  if (status_.state != DriverState::kRunning || !driver_) return;
  try {
    driver_->do_work();
  } catch (const std::exception& e) {
    fail(e.what());
    return;
  }
  // A driver that has run this long has recovered: its next failure is
  // retried quickly again.
  if (status_.consecutive_failures > 0 &&
      scheduler_.clock().now() - status_.since >= backoff_.max()) {
    status_.consecutive_failures = 0;
    backoff_.reset();
  }
  if (status_.state == DriverState::kRunning) schedule_work();
}

void DriverSupervisor::initiate_transmission(const v1::ModemTransmission& transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (status_.state != DriverState::kRunning || !driver_) {
    std::string why = "driver " + options_.driver_name + " is " +
                      describe(status_, scheduler_.clock().now());
    spdlog::debug("transmission not sent: {}", why);
    if (callbacks_.on_transmit_result) callbacks_.on_transmit_result(transmission, false, why);
    return;
  }
  try {
    driver_->initiate_transmission(transmission);
  } catch (const std::exception& e) {
    std::string why = e.what();
    fail(why);
    if (callbacks_.on_transmit_result) {
      callbacks_.on_transmit_result(transmission, false, "driver " + options_.driver_name + " failed: " + why);
    }
  }
}

DriverSpecificResult DriverSupervisor::check_driver_specific(const v1::ModemTransmission& request) const {
  ACOMMS_ASSERT_CORE_THREAD();
  if (status_.state != DriverState::kRunning || !driver_) {
    return driver_specific_error(DriverSpecificStatus::kUnavailable,
                                 "driver " + options_.driver_name + " is " +
                                     describe(status_, scheduler_.clock().now()),
                                 request);
  }
  DriverSpecificResult result = driver_->check_driver_specific(request);
  if (result.status != DriverSpecificStatus::kOk) result.error = "driver " + options_.driver_name + " " + result.error;
  return result;
}

void DriverSupervisor::send_driver_specific(const v1::ModemTransmission& request, double deadline_s,
                                            DriverSpecificDone done) {
  ACOMMS_ASSERT_CORE_THREAD();
  DriverSpecificResult checked = check_driver_specific(request);
  if (checked.status != DriverSpecificStatus::kOk) return done(std::move(checked));
  try {
    driver_->send_driver_specific(request, deadline_s, [name = options_.driver_name, done](DriverSpecificResult r) {
      if (r.status != DriverSpecificStatus::kOk) r.error = "driver " + name + ": " + r.error;
      done(std::move(r));
    });
  } catch (const std::exception& e) {
    std::string why = e.what();
    fail(why);
    done(driver_specific_error(DriverSpecificStatus::kAborted, "driver " + options_.driver_name + " failed: " + why,
                               request));
  }
}

void DriverSupervisor::fail(const std::string& reason) {
  scheduler_.cancel(work_task_);
  work_task_ = 0;
  if (driver_) {
    try {
      driver_->stop();
    } catch (const std::exception& e) {
      spdlog::warn("driver {}: error while stopping: {}", options_.driver_name, e.what());
    }
    carried_ += driver_->counters();  // a restarted driver counts from zero
    driver_.reset();
  }
  ++status_.failures;
  ++status_.consecutive_failures;
  status_.last_error = reason;
  auto delay = backoff_.next();
  status_.restart_at = scheduler_.clock().now() + std::chrono::duration_cast<core::Clock::time_point::duration>(delay);
  spdlog::error("driver {} failed: {}; restarting in {:.1f} s", options_.driver_name, reason,
                duration_to_seconds(delay));
  set_state(DriverState::kRestarting);
  restart_task_ = scheduler_.at(status_.restart_at, [this] { try_start(); });
}

void DriverSupervisor::set_state(DriverState state) {
  status_.state = state;
  status_.since = scheduler_.clock().now();
  if (on_status_) on_status_(status_);
}

std::chrono::nanoseconds DriverSupervisor::packet_air_time(int32_t rate, uint32_t num_frames) const {
  return driver_ ? driver_->packet_air_time(rate, num_frames) : Driver::packet_air_time(rate, num_frames);
}

std::chrono::nanoseconds DriverSupervisor::ack_time(int32_t rate) const {
  return driver_ ? driver_->ack_time(rate) : Driver::ack_time(rate);
}

double DriverSupervisor::sound_speed() const { return driver_ ? driver_->sound_speed() : Driver::sound_speed(); }

DriverCounters DriverSupervisor::counters() const {
  DriverCounters total = carried_;
  if (driver_) total += driver_->counters();
  return total;
}

}  // namespace acomms::link
