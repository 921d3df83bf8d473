#pragma once
// Decentralized TDMA with passive auto-discovery (Schneider (2013), section 2.4.3;
// goby-acomms had a similar mode). No master, no configured cycle and no
// control messages: each node builds its cycle from the nodes it has heard.
//
// Exact behaviour
// ---------------
// * Known world: this node plus every node it has heard (any transmission
//   with src >= 1, src != own id, in any slot or while waiting). With m known
//   ids the cycle has n = m + 1 slots of slot_seconds each: the known ids in
//   ascending order, each transmitting in its own slot, plus one blank slot in
//   which nobody of this world transmits and this node listens (its slot in
//   cycle() has src 0). This node transmits (DATA, dest -1, the configured
//   rate) only in its own slot.
// * Alignment: cycles lie on CycleGrid with length n * slot_seconds: cycle k
//   starts at midnight UTC + k * n * slot_seconds (or the epoch + ...), with
//   the silent remainder and realignment at midnight described there. Since
//   every cycle length is a whole number of slots from the same reference,
//   all nodes' slot boundaries coincide, whatever their views.
// * Blank position: blank_slot_index (blank_slot.h). The last slot, except
//   in "excited" cycles, where H(k, S) mod C == 0 (S: the sum of the known
//   ids, C: the coolness, H: a fixed 64-bit mix). By default (kAnywhere) an
//   excited blank takes a pseudo-random slot before the last; kFigure puts
//   it in the penultimate one, as Schneider (2013), Figure 2.10 and Table
//   2.7, has it (its equations 2.6-2.7 disagree and are not followed), and
//   kCongruence is goby-acomms' test. blank_slot.h says why kFigure cannot
//   make every network of 3+ nodes converge.
// * Discovery: a new id joins the known world when heard. The cycle in
//   progress is finished unchanged (it is still what the nodes sharing the
//   old view expect, so it stays collision-free); then, the cycle having
//   grown, the node waits, listening but silent, for the next boundary of
//   the new cycle length at or after the end of the old cycle. A discovery
//   made while already waiting re-plans the wait for the new length.
// * Expiry: at the start of each of its cycles the node drops every other
//   node not heard for more than expire_cycles * (current cycle length).
//   The cycle then shrinks, and the node waits for the next boundary of the
//   shorter cycle as above.
// * Power-on: the known world is the node alone (2 slots); it waits for the
//   next boundary.
// * set_cycle is refused (std::invalid_argument): the cycle is what the node
//   has heard, and a configured one belongs to the "fixed" MAC.
//
// Core thread only, like every Mac (mac.h), and checked (core/core_thread.h).

#include <map>
#include <optional>
#include <vector>

#include "core/scheduler.h"
#include "mac/blank_slot.h"
#include "mac/cycle_grid.h"
#include "mac/mac.h"

namespace acomms::mac {

struct AutoDiscoveryConfig {
  double slot_seconds = 10;
  int32_t rate = 0;
  uint32_t coolness = 3;       // C >= 1; Schneider (2013) recommends network size + 1
  uint32_t expire_cycles = 5;  // >= 1
  BlankRule blank_rule = kDefaultBlankRule;
  std::optional<double> epoch;  // unset: midnight UTC
};

class AutoDiscoveryMac final : public Mac {
 public:
  // What the node is doing now (for simulations and status).
  enum class Activity { kOff, kWaiting, kSending, kBlank, kListening };

  // Throws std::invalid_argument for own_id < 1, slot_seconds < 1 ms,
  // coolness 0 or expire_cycles 0.
  AutoDiscoveryMac(const AutoDiscoveryConfig& config, int32_t own_id, core::Scheduler& scheduler);
  ~AutoDiscoveryMac() override;

  void start(Transmit transmit) override;
  void stop() override;
  // Always throws std::invalid_argument (see above).
  void set_cycle(const Cycle& cycle) override;
  std::string cycle_not_settable_reason() const override {
    return "the \"auto_discovery\" MAC builds its cycle from the nodes it hears; it cannot be set";
  }
  // The cycle in progress, or the last one (before the first cycle: this
  // node and the blank). The blank slot has src 0.
  const Cycle& cycle() const override { return cycle_; }
  void on_receive(const v1::ModemTransmission& transmission) override;
  // known_ids() and the blank rule.
  MacStatus status() const override;

  int32_t own_id() const { return own_id_; }
  BlankRule blank_rule() const { return config_.blank_rule; }
  // The known world, this node included, ascending.
  std::vector<int32_t> known_ids() const;
  Activity activity() const;
  // True from a cycle's start to its end; false while waiting for a boundary.
  bool in_cycle() const { return in_cycle_; }
  core::Clock::time_point cycle_start() const { return cycle_start_; }
  int64_t cycle_count() const { return cycle_count_; }

 private:
  Nanoseconds cycle_length() const;
  void plan(core::Clock::time_point t);
  void begin_cycle(CycleGrid::CycleStart start);
  void begin_slot(size_t index);
  void end_cycle();
  bool expire(core::Clock::time_point now);
  void build_cycle(int64_t count);
  void cancel_task();

  core::Scheduler& scheduler_;
  const AutoDiscoveryConfig config_;
  const int32_t own_id_;
  const Nanoseconds slot_;
  std::map<int32_t, core::Clock::time_point> last_heard_;  // other nodes
  Cycle cycle_;
  bool running_ = false;
  bool in_cycle_ = false;
  size_t slot_index_ = 0;
  core::Clock::time_point cycle_start_{};
  int64_t cycle_count_ = 0;
  Transmit transmit_;
  std::optional<core::Scheduler::TaskId> task_;
};

}  // namespace acomms::mac
