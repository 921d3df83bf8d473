#pragma once
// Fixed decentralized TDMA: every node is configured with the same cycle and
// transmits in the slots whose src is its own id. No master, no messages:
// the nodes agree only because their clocks agree on UTC, so cycle k starts
// at reference + k * cycle_length (see CycleGrid: the reference is the
// configured epoch or midnight UTC, with realignment at every midnight).
// Slot i of a cycle starts after the lengths of slots 0..i-1, in integer
// nanoseconds, so slot times are exact multiples, never drifting sums.
//
// A node that starts mid-cycle joins at the next slot boundary of the cycle
// in progress (its slots are known in advance, so there is nothing to wait
// for). set_cycle takes effect at the next cycle boundary of the current
// grid; the new cycle then starts at its own next boundary at or after that
// instant (the same instant when the lengths agree), so all nodes switching
// to the same new cycle stay aligned.

#include <optional>
#include <vector>

#include "core/scheduler.h"
#include "mac/cycle_grid.h"
#include "mac/mac.h"

namespace acomms::mac {

class FixedMac final : public Mac {
 public:
  // `epoch`: seconds since the Unix epoch the cycles align to (unset:
  // midnight UTC). Throws std::invalid_argument for a bad cycle.
  FixedMac(Cycle cycle, int32_t own_id, std::optional<double> epoch, core::Scheduler& scheduler);
  ~FixedMac() override;

  void start(Transmit transmit) override;
  void stop() override;
  void set_cycle(const Cycle& cycle) override;
  const Cycle& cycle() const override { return cycle_; }
  // Everything is fixed by configuration: nothing to learn.
  void on_receive(const v1::ModemTransmission&) override {}

 private:
  void adopt(Cycle cycle);
  // Plans the first slot starting at or after `t`.
  void plan_from(core::Clock::time_point t);
  void schedule_slot(size_t index, core::Clock::time_point cycle_start);
  void begin_slot(size_t index, core::Clock::time_point cycle_start);

  core::Scheduler& scheduler_;
  const int32_t own_id_;
  const std::optional<double> epoch_;
  Cycle cycle_;
  std::vector<Nanoseconds> offsets_;  // slot i starts offsets_[i] into the cycle
  CycleGrid grid_;
  std::optional<Cycle> pending_;
  Transmit transmit_;
  std::optional<core::Scheduler::TaskId> task_;
};

}  // namespace acomms::mac
