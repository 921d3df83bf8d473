#pragma once
// The smallest acoustic channel that can judge a TDMA MAC: one hop, every
// node hears every transmission, and transmissions that start at the same
// instant (the same slot, since all slot boundaries lie on one grid) collide.
//
// Model, exactly as implemented
// -----------------------------
// * A node is heard only while it listens: a node that transmits in a slot
//   hears nothing in it (half duplex), and a node that is not switched on
//   hears nothing.
// * One transmitter in a slot: every listening node receives it.
// * Two or more: each listening node, independently, loses all of them with
//   probability p_collide, and otherwise receives all of them (capture of
//   overlapping packets is what p_collide < 1 stands for).
// * Receptions are delivered `delay` after the slot start (the end of the
//   packet, before the next slot), in id order.
// Random draws come from a generator seeded at construction, in a fixed
// order, so a run is repeatable.

#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "acomms/v1/modem_transmission.pb.h"
#include "core/scheduler.h"

namespace acomms::eval {

class SimulatedChannel {
 public:
  using Receive = std::function<void(const v1::ModemTransmission&)>;

  // What happened in one slot, after delivery.
  struct SlotOutcome {
    core::Clock::time_point start;
    std::vector<int32_t> transmitters;  // ascending
    // listener -> the ids it received (listeners that received nothing are
    // absent).
    std::map<int32_t, std::vector<int32_t>> received;
    bool collision() const { return transmitters.size() > 1; }
  };
  using Observer = std::function<void(const SlotOutcome&)>;

  SimulatedChannel(core::Scheduler& scheduler, std::chrono::nanoseconds delay, double p_collide,
                   uint64_t seed);

  // A node on the channel, off until switched on.
  void attach(int32_t id, Receive receive);
  void switch_on(int32_t id);
  // `id` starts `transmission` now.
  void transmit(int32_t id, const v1::ModemTransmission& transmission);
  // Called after each slot with at least one transmitter is delivered.
  void set_observer(Observer observer) { observer_ = std::move(observer); }

 private:
  struct Node {
    Receive receive;
    bool on = false;
  };
  void deliver(core::Clock::time_point start);

  core::Scheduler& scheduler_;
  const std::chrono::nanoseconds delay_;
  const double p_collide_;
  std::mt19937_64 random_;
  std::map<int32_t, Node> nodes_;
  // Transmissions by start time, awaiting delivery.
  std::map<core::Clock::time_point, std::map<int32_t, v1::ModemTransmission>> pending_;
  Observer observer_;
};

}  // namespace acomms::eval
