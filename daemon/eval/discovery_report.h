#pragma once
// The discovery evaluation as text, for a person and for tools: one
// scenario (discovery_simulation.h) as a per-slot table, and a Monte Carlo
// (discovery_monte_carlo.h) as CSV. Kept apart from the simulation so that
// the simulation stays a library with no output of its own, and the text's
// shape (which tests and scripts read) is decided in one place.
//
// Threads: pure functions (any thread).

#include <string>
#include <vector>

#include "eval/discovery_monte_carlo.h"
#include "eval/discovery_simulation.h"

namespace acomms::eval {

// The per-slot table, a summary comment and the final line
// "converged_at_s=T collisions=K" (or "converged_at_s=never collisions=K").
std::string format_discovery(const DiscoveryScenario& scenario, const DiscoveryResult& result);

// "nodes,coolness,p_collide,collision_prob,mean_discovery_slots,fail_pct".
std::string format_discovery_csv(const std::vector<DiscoveryPoint>& points);

}  // namespace acomms::eval
