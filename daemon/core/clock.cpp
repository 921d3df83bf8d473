#include "core/clock.h"

#include "util/seconds.h"

namespace acomms::core {

double Clock::now_seconds() const {
  return util::seconds_since_epoch(now());
}

Clock::time_point SimulatedClock::now() const {
  std::lock_guard lock(mutex_);
  return now_;
}

void SimulatedClock::set(time_point t) {
  std::lock_guard lock(mutex_);
  now_ = t;
}

void SimulatedClock::advance(std::chrono::system_clock::duration d) {
  std::lock_guard lock(mutex_);
  now_ += d;
}

}  // namespace acomms::core
