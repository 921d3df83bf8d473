#pragma once
// The auto-discovery evaluation (`acommsctl sim mac-discovery`): real
// AutoDiscoveryMac objects, one per node, on one SimulatedScheduler, talking
// through a SimulatedChannel (one hop, collisions lose packets with
// probability p_collide). A library function with no I/O but the text it
// returns.
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
// * Monte Carlo, per trial: n distinct ids drawn uniformly from 1..127
//   (7-bit modem ids, 0 being broadcast); a base time drawn uniformly from
//   the day (leaving room for the horizon before midnight); each node powers
//   on at base + U[0, start_window_cycles * (n + 1) * slot_seconds), rounded
//   to the millisecond. Trial j of a given n uses the same ids, start times
//   and channel random stream for every coolness and p_collide (common
//   random numbers), from a SplitMix64 stream seeded by (seed, n, j).
//     collision_prob        collided transmissions / transmissions, pooled
//                           over the trials, before convergence (or the
//                           horizon)
//     mean_discovery_slots  mean over converged trials of (converged_at -
//                           the last power-on) / slot_seconds
//     fail_pct              trials not converged within horizon_cycles
//                           cycles of the full network ((n + 1) slots) after
//                           the last power-on

#include <cstdint>
#include <optional>
#include <string>
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

// The per-slot table, a summary comment and the final line
// "converged_at_s=T collisions=K" (or "converged_at_s=never collisions=K").
std::string format_discovery(const DiscoveryScenario& scenario, const DiscoveryResult& result);

struct DiscoveryMonteCarloConfig {
  std::vector<int> sizes = {3, 4, 5, 6};
  // 0 stands for "network size + 1" (Schneider (2013), section 2.4.3,
  // recommends it).
  std::vector<uint32_t> coolness = {0};
  std::vector<double> p_collide = {1, 0.75, 0.5};
  int trials = 200;
  double slot_seconds = 15;
  uint32_t expire_cycles = 5;
  mac::BlankRule blank_rule = mac::kDefaultBlankRule;
  double start_window_cycles = 4;
  double horizon_cycles = 200;
  uint64_t seed = 1;
};

struct DiscoveryPoint {
  int nodes = 0;
  uint32_t coolness = 0;
  double p_collide = 0;
  double collision_prob = 0;
  double mean_discovery_slots = 0;  // NaN when no trial converged
  double fail_pct = 0;
};

std::vector<DiscoveryPoint> simulate_discovery_monte_carlo(const DiscoveryMonteCarloConfig& config);

// "nodes,coolness,p_collide,collision_prob,mean_discovery_slots,fail_pct".
std::string format_discovery_csv(const std::vector<DiscoveryPoint>& points);

}  // namespace acomms::eval
