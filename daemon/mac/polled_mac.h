#pragma once
// Centralized polling: this node is the master and owns the cycle.
//
// At the start of every slot the master asks its driver to initiate the
// slot's transmission with src = slot.src. When src is another node, the
// driver polls it (third-party initiation) and that node's driver answers
// with its data, so the other nodes need no clock, no cycle and no MAC of
// their own ("none"). Because one clock rules, the cycle is not aligned to
// UTC: the first slot starts at start() and cycles follow back to back,
// each slot starting exactly `seconds` after the previous one (times are
// computed from the schedule, never from when a task happened to run, so
// they do not drift).
//
// set_cycle takes effect at the next cycle boundary: the cycle in progress
// is finished as planned, and the new one starts right after its last slot.

#include <optional>

#include "core/scheduler.h"
#include "mac/cycle_grid.h"
#include "mac/mac.h"

namespace acomms::mac {

class PolledMac final : public Mac {
 public:
  // Throws std::invalid_argument for a bad cycle (see check_cycle).
  PolledMac(Cycle cycle, core::Scheduler& scheduler);
  ~PolledMac() override;

  void start(Transmit transmit) override;
  void stop() override;
  void set_cycle(const Cycle& cycle) override;
  const Cycle& cycle() const override { return cycle_; }
  // The master learns nothing from what it hears.
  void on_receive(const v1::ModemTransmission&) override {}

 private:
  void begin_slot(size_t index, core::Clock::time_point when);

  core::Scheduler& scheduler_;
  Cycle cycle_;
  std::optional<Cycle> pending_;
  Transmit transmit_;
  std::optional<core::Scheduler::TaskId> task_;
};

}  // namespace acomms::mac
