#pragma once
// The auto-discovery evaluation (`acommsctl sim mac-discovery`): real
// AutoDiscoveryMac objects, one per node, on one SimulatedScheduler, talking
// through a SimulatedChannel (one hop, collisions lose packets with
// probability p_collide). A library function with no I/O; its text is
// discovery_report.h's, and many random runs are discovery_monte_carlo.h's.
//
// Definitions, exactly as implemented
// -----------------------------------
// * Time is seconds since midnight UTC of a fixed simulated day
//   (2024-06-01); node i powers on at start_s[i].
// * Converged: every node is on and inside a cycle, all cycles started at the
//   same instant and are the same slot list, that list holds every node, and
//   no slot has had two transmitters since. converged_at_s is the start of
//   the first cycle from which this held to the end of the run. Once it
//   holds for a whole cycle it cannot break (everyone transmits once per
//   cycle, alone, so nobody expires anybody), so a run stops two cycles after
//   it first holds, or at the horizon (then: never, unless it holds there).
// * Collisions: slots with two or more transmitters, from the first
//   power-on to convergence (or to the end of the run).
//
// Threads: none of its own; a call uses only what it is given (any thread).

#include <cstdint>
#include <optional>
#include <vector>

#include "mac/blank_slot.h"

namespace acomms::eval {

struct DiscoveryScenario {
  std::vector<int32_t> ids;
  std::vector<double> start_s;  // per node, seconds since midnight UTC
  double slot_seconds = 15;
  uint32_t coolness = 3;
  uint32_t expire_cycles = 5;
  mac::BlankRule blank_rule = mac::kDefaultBlankRule;
  double p_collide = 1;
  uint64_t seed = 1;
  // Give up this long after the last power-on, in cycles of the full
  // network ((ids + 1) slots).
  double horizon_cycles = 200;
};

enum class NodeAction { kOff, kWait, kSend, kBlank, kListen };

struct NodeSlot {
  NodeAction action = NodeAction::kOff;
  bool cycle_start = false;            // a cycle of this node starts here
  std::vector<int32_t> cycle;          // its slots then (0: blank)
  std::vector<int32_t> discovered;     // heard for the first time in this slot
  std::vector<int32_t> expired;        // dropped at this slot's start
};

struct SlotTrace {
  double time_s = 0;
  std::vector<NodeSlot> nodes;         // in scenario order
  std::vector<int32_t> transmitters;   // ascending
  // Listeners that lost a collision.
  std::vector<int32_t> lost;
};

struct DiscoveryResult {
  std::optional<double> converged_at_s;
  double last_start_s = 0;
  double cycle_seconds = 0;            // of the shared cycle, when converged
  int64_t collisions = 0;
  int64_t transmissions = 0;           // before convergence (or the end)
  int64_t collided_transmissions = 0;  // of those, in a slot with another
  std::vector<SlotTrace> trace;        // when asked for
};

// Throws std::invalid_argument for an empty or duplicated id list, an id
// < 1, a start_s list whose size is neither 1 (all nodes) nor the number of
// ids, p_collide outside [0, 1], a non-positive horizon, or a bad MAC
// parameter.
DiscoveryResult simulate_discovery(const DiscoveryScenario& scenario, bool keep_trace);

}  // namespace acomms::eval
