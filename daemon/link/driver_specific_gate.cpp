#include "link/driver_specific_gate.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "core/core_thread.h"

namespace acomms::link {

DriverSpecificGate::DriverSpecificGate(const core::Clock* clock, core::Scheduler* scheduler)
    : clock_(clock), scheduler_(scheduler) {}

DriverSpecificGate::~DriverSpecificGate() { abort("the link stopped"); }

double DriverSpecificGate::now_s() const { return clock_ == nullptr ? 0 : clock_->now_seconds(); }

void DriverSpecificGate::wait(v1::ModemTransmission request, double deadline_s, DriverSpecificDone done) {
  ACOMMS_ASSERT_CORE_THREAD();
  Waiting w;
  w.id = next_id_++;
  w.since_s = now_s();
  w.deadline_s = deadline_s;
  w.request = std::move(request);
  w.done = std::move(done);
  if (scheduler_ != nullptr && std::isfinite(deadline_s)) {
    auto delay = std::chrono::duration_cast<std::chrono::system_clock::duration>(
        std::chrono::duration<double>(std::max(0.0, deadline_s - w.since_s)));
    w.timer = scheduler_->after(delay, [this, id = w.id] { expire(id); });
  }
  spdlog::debug("link: driver-specific {} waits for this node's slot (deadline in {:.1f} s)",
                describe_driver_specific(w.request), deadline_s - w.since_s);
  waiting_.push_back(std::move(w));
}

void DriverSpecificGate::expire(uint64_t id) {
  ACOMMS_ASSERT_CORE_THREAD();
  for (auto it = waiting_.begin(); it != waiting_.end(); ++it) {
    if (it->id != id) continue;
    Waiting w = std::move(*it);
    waiting_.erase(it);
    DriverSpecificResult result = driver_specific_error(
        DriverSpecificStatus::kDeadlineExceeded,
        "the deadline passed after " + std::to_string(static_cast<int>(std::lround(now_s() - w.since_s))) +
            " s waiting for this node's slot (or a poll): the request was never sent",
        w.request);
    result.waited_s = now_s() - w.since_s;
    w.done(std::move(result));
    return;
  }
}

bool DriverSpecificGate::send_next(Driver& driver, const char* how) {
  ACOMMS_ASSERT_CORE_THREAD();
  double now = now_s();
  while (!waiting_.empty()) {
    Waiting w = std::move(waiting_.front());
    waiting_.pop_front();
    if (scheduler_ != nullptr && w.timer != 0) scheduler_->cancel(w.timer);
    double waited = now - w.since_s;
    if (clock_ != nullptr && now >= w.deadline_s) {
      auto result = driver_specific_error(DriverSpecificStatus::kDeadlineExceeded,
                                          "the deadline passed while waiting for this node's slot", w.request);
      result.waited_s = waited;
      w.done(std::move(result));
      continue;
    }
    spdlog::info("link: driver-specific {} goes out in {} after {:.1f} s", describe_driver_specific(w.request), how,
                 waited);
    driver.send_driver_specific(w.request, w.deadline_s, [waited, done = std::move(w.done)](DriverSpecificResult r) {
      r.waited_s = waited;
      done(std::move(r));
    });
    return true;
  }
  return false;
}

void DriverSpecificGate::abort(const std::string& why) {
  while (!waiting_.empty()) {
    Waiting w = std::move(waiting_.front());
    waiting_.pop_front();
    if (scheduler_ != nullptr && w.timer != 0) scheduler_->cancel(w.timer);
    w.done(driver_specific_error(DriverSpecificStatus::kUnavailable, why + " before the request was sent", w.request));
  }
}

}  // namespace acomms::link
