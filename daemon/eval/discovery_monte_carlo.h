#pragma once
// The discovery Monte Carlo (`acommsctl sim mac-discovery --monte-carlo`):
// how often auto-discovery collides, how long it takes and how often it
// fails, over many random networks, per network size, coolness and
// p_collide. Each trial is one scenario of discovery_simulation.h, whose
// definitions (converged, collisions) it uses.
//
// Definitions, exactly as implemented
// -----------------------------------
// Per trial: n distinct ids drawn uniformly from 1..127 (7-bit modem ids, 0
// being broadcast); a base time drawn uniformly from the day (leaving room
// for the horizon before midnight); each node powers on at base + U[0,
// start_window_cycles * (n + 1) * slot_seconds), rounded to the
// millisecond. Trial j of a given n uses the same ids, start times and
// channel random stream for every coolness and p_collide (common random
// numbers), from a SplitMix64 stream seeded by (seed, n, j).
//   collision_prob        collided transmissions / transmissions, pooled
//                         over the trials, before convergence (or the
//                         horizon)
//   mean_discovery_slots  mean over converged trials of (converged_at -
//                         the last power-on) / slot_seconds
//   fail_pct              trials not converged within horizon_cycles
//                         cycles of the full network ((n + 1) slots) after
//                         the last power-on
//
// Threads: none of its own; a call uses only what it is given (any thread).

#include <cstdint>
#include <vector>

#include "mac/blank_slot.h"

namespace acomms::eval {

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

// Throws std::invalid_argument for trials < 1 or a size outside 1..127.
std::vector<DiscoveryPoint> simulate_discovery_monte_carlo(const DiscoveryMonteCarloConfig& config);

}  // namespace acomms::eval
