#pragma once
// Timed work for the core thread, against a Clock.
//
// MAC slots, propagation delays in the simulator and expiry timers all say
// "run this at time t". With the AsioScheduler that is a timer on the core
// thread's event loop, in real time. With the SimulatedScheduler a test
// drives time itself (run_until), so a whole network of nodes sharing one
// scheduler runs in one process, deterministically and much faster than
// real time. Every task runs on the thread that drives the scheduler.

#include <asio/io_context.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <unordered_map>

#include "core/clock.h"

namespace acomms::core {

class Scheduler {
 public:
  using Task = std::function<void()>;
  using TaskId = uint64_t;
  virtual ~Scheduler() = default;

  virtual const Clock& clock() const = 0;
  // Runs `task` at `when` (at once, but not inside this call, if `when` has
  // passed). Tasks due at the same time run in the order they were scheduled.
  virtual TaskId at(Clock::time_point when, Task task) = 0;
  TaskId after(std::chrono::system_clock::duration delay, Task task) {
    return at(clock().now() + delay, std::move(task));
  }
  // Forgets a task that has not run yet; unknown ids are ignored.
  virtual void cancel(TaskId id) = 0;
};

// Real time: tasks are timers on an asio io_context (the core thread's).
class AsioScheduler final : public Scheduler {
 public:
  AsioScheduler(asio::io_context& context, const Clock& clock);
  ~AsioScheduler() override;
  const Clock& clock() const override { return clock_; }
  TaskId at(Clock::time_point when, Task task) override;
  void cancel(TaskId id) override;

 private:
  struct Timer;
  asio::io_context& context_;
  const Clock& clock_;
  TaskId next_id_ = 1;
  std::unordered_map<TaskId, std::shared_ptr<Timer>> timers_;
};

// Simulated time: nothing runs until the owner says how far time goes.
class SimulatedScheduler final : public Scheduler {
 public:
  explicit SimulatedScheduler(Clock::time_point start) : clock_(start) {}
  const Clock& clock() const override { return clock_; }
  TaskId at(Clock::time_point when, Task task) override;
  void cancel(TaskId id) override;

  // Runs every task due up to `until` in time order, setting the clock to
  // each task's time as it runs (tasks may schedule more), then sets the
  // clock to `until`. Returns the number of tasks run.
  size_t run_until(Clock::time_point until);
  size_t run_for(std::chrono::system_clock::duration duration) {
    return run_until(clock_.now() + duration);
  }
  size_t pending() const { return tasks_.size(); }

 private:
  SimulatedClock clock_;
  TaskId next_id_ = 1;
  // (time, id): ids ascend, so equal times keep scheduling order.
  std::map<std::pair<Clock::time_point, TaskId>, Task> tasks_;
  std::unordered_map<TaskId, Clock::time_point> when_;
};

}  // namespace acomms::core
