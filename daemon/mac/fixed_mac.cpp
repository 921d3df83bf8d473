#include "mac/fixed_mac.h"

#include <utility>

#include "core/core_thread.h"
#include "util/seconds.h"

namespace acomms::mac {
namespace {

// The grid needs some positive length before the cycle is checked.
Nanoseconds length_of(const Cycle& cycle) {
  Nanoseconds total{0};
  for (const Slot& slot : cycle) total += to_nanoseconds(slot.seconds);
  return total > Nanoseconds{0} ? total : Nanoseconds{1};
}

}  // namespace

FixedMac::FixedMac(Cycle cycle, int32_t own_id, std::optional<double> epoch,
                   core::Scheduler& scheduler)
    : scheduler_(scheduler), own_id_(own_id), epoch_(epoch), grid_(epoch, length_of(cycle)) {
  check_cycle(cycle, "mac.slot");
  adopt(std::move(cycle));
}

FixedMac::~FixedMac() { stop(); }

void FixedMac::adopt(Cycle cycle) {
  cycle_ = std::move(cycle);
  offsets_.clear();
  Nanoseconds offset{0};
  for (const Slot& slot : cycle_) {
    offsets_.push_back(offset);
    offset += to_nanoseconds(slot.seconds);
  }
  grid_ = CycleGrid(epoch_, offset);
}

void FixedMac::start(Transmit transmit) {
  ACOMMS_ASSERT_CORE_THREAD();
  stop();
  transmit_ = std::move(transmit);
  if (pending_) adopt(*std::exchange(pending_, std::nullopt));
  plan_from(scheduler_.clock().now());
}

void FixedMac::stop() {
  ACOMMS_ASSERT_CORE_THREAD();
  if (task_) scheduler_.cancel(*task_);
  task_.reset();
}

void FixedMac::set_cycle(const Cycle& cycle) {
  ACOMMS_ASSERT_CORE_THREAD();
  check_cycle(cycle, "cycle");
  pending_ = cycle;
}

void FixedMac::plan_from(core::Clock::time_point t) {
  if (std::optional<CycleGrid::CycleStart> current = grid_.containing(t)) {
    for (size_t i = 0; i < cycle_.size(); ++i) {
      if (current->start + offsets_[i] >= t) {
        schedule_slot(i, current->start);
        return;
      }
    }
  }
  schedule_slot(0, grid_.next(t).start);
}

void FixedMac::schedule_slot(size_t index, core::Clock::time_point cycle_start) {
  task_ = scheduler_.at(cycle_start + offsets_[index],
                        [this, index, cycle_start] { begin_slot(index, cycle_start); });
}

void FixedMac::begin_slot(size_t index, core::Clock::time_point cycle_start) {
  ACOMMS_ASSERT_CORE_THREAD();
  task_.reset();
  if (index == 0 && pending_) {
    // A boundary of the old grid: switch, and wait for the new grid's next
    // boundary unless it is this very instant.
    adopt(*std::exchange(pending_, std::nullopt));
    const CycleGrid::CycleStart next = grid_.next(cycle_start);
    if (next.start != cycle_start) {
      schedule_slot(0, next.start);
      return;
    }
  }
  const Slot slot = cycle_[index];
  const core::Clock::time_point slot_start = cycle_start + offsets_[index];
  if (index + 1 < cycle_.size()) {
    schedule_slot(index + 1, cycle_start);
  } else {
    // Past the last slot: the next cycle of the grid (after midnight's
    // silent remainder, if this was the day's last cycle).
    plan_from(cycle_start + grid_.cycle_length());
  }
  if (slot.src != own_id_ || !transmit_) return;
  const double seconds = util::seconds_since_epoch(slot_start);
  transmit_(slot_transmission(slot, seconds));
}

}  // namespace acomms::mac
