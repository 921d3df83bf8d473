#pragma once
// Real time, sped up: the fake_micromodem executable runs its modems on an
// asio event loop whose clock runs `scale` times faster than the wall
// clock (scale 1 = real time). A driver under test must then use the same
// scale for its own timeouts; at scale 1 nothing needs to agree.
// Tests in one process use core::SimulatedScheduler instead.

#include <asio/io_context.hpp>

#include <memory>
#include <unordered_map>

#include "core/scheduler.h"

namespace acomms::fake_micromodem {

// now = origin + (wall clock - origin) * scale: starts at the real time.
class ScaledClock final : public core::Clock {
 public:
  explicit ScaledClock(double scale);
  time_point now() const override;
  double scale() const { return scale_; }

 private:
  double scale_;
  time_point origin_;
};

class ScaledScheduler final : public core::Scheduler {
 public:
  ScaledScheduler(asio::io_context& context, double scale);
  ~ScaledScheduler() override;
  const core::Clock& clock() const override { return clock_; }
  TaskId at(core::Clock::time_point when, Task task) override;
  void cancel(TaskId id) override;

 private:
  struct Timer;
  asio::io_context& context_;
  ScaledClock clock_;
  TaskId next_id_ = 1;
  std::unordered_map<TaskId, std::shared_ptr<Timer>> timers_;
};

}  // namespace acomms::fake_micromodem
