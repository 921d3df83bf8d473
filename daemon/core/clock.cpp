#include "core/clock.h"

namespace acomms::core {

double Clock::now_seconds() const {
  return std::chrono::duration<double>(now().time_since_epoch()).count();
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
