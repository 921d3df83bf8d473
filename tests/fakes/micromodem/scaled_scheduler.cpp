#include "scaled_scheduler.h"

#include <asio/steady_timer.hpp>

#include <stdexcept>

namespace acomms::fake_micromodem {

ScaledClock::ScaledClock(double scale) : scale_(scale), origin_(std::chrono::system_clock::now()) {
  if (!(scale > 0)) throw std::invalid_argument("time scale must be > 0");
}

ScaledClock::time_point ScaledClock::now() const {
  auto real = std::chrono::system_clock::now() - origin_;
  return origin_ + std::chrono::duration_cast<std::chrono::system_clock::duration>(real * scale_);
}

struct ScaledScheduler::Timer {
  explicit Timer(asio::io_context& context) : timer(context) {}
  asio::steady_timer timer;
};

ScaledScheduler::ScaledScheduler(asio::io_context& context, double scale)
    : context_(context), clock_(scale) {}

ScaledScheduler::~ScaledScheduler() {
  for (auto& [id, timer] : timers_) timer->timer.cancel();
}

core::Scheduler::TaskId ScaledScheduler::at(core::Clock::time_point when, Task task) {
  TaskId id = next_id_++;
  auto timer = std::make_shared<Timer>(context_);
  auto simulated = when - clock_.now();
  timer->timer.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      simulated / clock_.scale()));
  timers_.emplace(id, timer);
  timer->timer.async_wait([this, id, timer, task = std::move(task)](const std::error_code& error) {
    if (error) return;  // cancelled
    timers_.erase(id);
    task();
  });
  return id;
}

void ScaledScheduler::cancel(TaskId id) {
  auto it = timers_.find(id);
  if (it == timers_.end()) return;
  it->second->timer.cancel();
  timers_.erase(it);
}

}  // namespace acomms::fake_micromodem
