#include "mac/polled_mac.h"

#include <utility>

#include "core/core_thread.h"
#include "util/seconds.h"

namespace acomms::mac {

PolledMac::PolledMac(Cycle cycle, core::Scheduler& scheduler)
    : scheduler_(scheduler), cycle_(std::move(cycle)) {
  check_cycle(cycle_, "mac.slot");
}

PolledMac::~PolledMac() { stop(); }

void PolledMac::start(Transmit transmit) {
  ACOMMS_ASSERT_CORE_THREAD();
  stop();
  transmit_ = std::move(transmit);
  if (pending_) cycle_ = *std::exchange(pending_, std::nullopt);
  const core::Clock::time_point now = scheduler_.clock().now();
  task_ = scheduler_.at(now, [this, now] { begin_slot(0, now); });
}

void PolledMac::stop() {
  ACOMMS_ASSERT_CORE_THREAD();
  if (task_) scheduler_.cancel(*task_);
  task_.reset();
}

void PolledMac::set_cycle(const Cycle& cycle) {
  ACOMMS_ASSERT_CORE_THREAD();
  check_cycle(cycle, "cycle");
  pending_ = cycle;
}

void PolledMac::begin_slot(size_t index, core::Clock::time_point when) {
  ACOMMS_ASSERT_CORE_THREAD();
  task_.reset();
  // A cycle boundary: the place where a new cycle may take over.
  if (index == 0 && pending_) cycle_ = *std::exchange(pending_, std::nullopt);
  const Slot slot = cycle_[index];
  const core::Clock::time_point next = when + to_nanoseconds(slot.seconds);
  const size_t next_index = (index + 1) % cycle_.size();
  // Scheduled before transmitting, so that a transmit callback that stops
  // the MAC cancels the right task.
  task_ = scheduler_.at(next, [this, next_index, next] { begin_slot(next_index, next); });
  const double seconds = util::seconds_since_epoch(when);
  if (transmit_) transmit_(slot_transmission(slot, seconds));
}

}  // namespace acomms::mac
