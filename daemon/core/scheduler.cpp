#include "core/scheduler.h"

#include <asio/post.hpp>
#include <asio/system_timer.hpp>

namespace acomms::core {

struct AsioScheduler::Timer {
  explicit Timer(asio::io_context& context) : timer(context) {}
  asio::system_timer timer;
};

AsioScheduler::AsioScheduler(asio::io_context& context, const Clock& clock)
    : context_(context), clock_(clock) {}

AsioScheduler::~AsioScheduler() {
  for (auto& [id, timer] : timers_) timer->timer.cancel();
}

Scheduler::TaskId AsioScheduler::at(Clock::time_point when, Task task) {
  TaskId id = next_id_++;
  auto timer = std::make_shared<Timer>(context_);
  // The Clock, not the system clock, says when: convert to a delay from now.
  timer->timer.expires_after(when - clock_.now());
  timers_.emplace(id, timer);
  timer->timer.async_wait([this, id, timer, task = std::move(task)](const std::error_code& error) {
    if (error) return;  // cancelled
    timers_.erase(id);
    task();
  });
  return id;
}

void AsioScheduler::cancel(TaskId id) {
  auto it = timers_.find(id);
  if (it == timers_.end()) return;
  it->second->timer.cancel();
  timers_.erase(it);
}

Scheduler::TaskId SimulatedScheduler::at(Clock::time_point when, Task task) {
  TaskId id = next_id_++;
  // A time already past means "as soon as possible": now, after what is due.
  when = std::max(when, clock_.now());
  tasks_.emplace(std::make_pair(when, id), std::move(task));
  when_.emplace(id, when);
  return id;
}

void SimulatedScheduler::cancel(TaskId id) {
  auto it = when_.find(id);
  if (it == when_.end()) return;
  tasks_.erase({it->second, id});
  when_.erase(it);
}

size_t SimulatedScheduler::run_until(Clock::time_point until) {
  size_t ran = 0;
  while (!tasks_.empty() && tasks_.begin()->first.first <= until) {
    auto first = tasks_.begin();
    clock_.set(first->first.first);
    Task task = std::move(first->second);
    when_.erase(first->first.second);
    tasks_.erase(first);
    task();
    ++ran;
  }
  if (clock_.now() < until) clock_.set(until);
  return ran;
}

}  // namespace acomms::core
