// The auto-discovery evaluation (daemon/eval/discovery_simulation.h): real
// AutoDiscoveryMac nodes on the simulated channel converge, or are shown not
// to, and a seed gives the same Monte Carlo numbers every time.

#include "eval/discovery_simulation.h"

#include <gtest/gtest.h>

#include <vector>

#include "eval/discovery_monte_carlo.h"
#include "eval/discovery_report.h"
#include "mac/blank_slot.h"

namespace acomms::eval {
namespace {

// Schneider (2013), Table 2.7: two vehicles, 15 s slots, C = size + 1 = 3.
// A shared collision-free cycle within ten cycles, whatever the power-on.
TEST(DiscoverySimulation, Schneider2013Table27ConvergesWithinTenCycles) {
  const std::vector<std::vector<double>> starts = {
      {0}, {0, 20}, {7, 100}, {3600, 3600}, {43210.5, 43290}, {86000, 86100}, {500, 520}};
  for (const std::vector<double>& start : starts) {
    DiscoveryScenario scenario;
    scenario.ids = {1, 2};
    scenario.start_s = start;
    scenario.slot_seconds = 15;
    scenario.coolness = 3;
    DiscoveryResult result = simulate_discovery(scenario, false);
    ASSERT_TRUE(result.converged_at_s.has_value()) << start.front();
    EXPECT_EQ(result.cycle_seconds, 45);
    EXPECT_LE(*result.converged_at_s - result.last_start_s, 10 * 45) << start.front();
  }
  DiscoveryScenario scenario;
  scenario.ids = {1, 2};
  scenario.start_s = {0};
  scenario.slot_seconds = 15;
  scenario.coolness = 3;
  DiscoveryResult result = simulate_discovery(scenario, true);
  // Both lone (30 s cycles) collide until node 2's cycle at 120 s is
  // excited and node 1's is not; both discover there, wait for the 45 s grid
  // (180 s) and share [1 2 _] from then on.
  EXPECT_EQ(*result.converged_at_s, 180);
  EXPECT_EQ(result.collisions, 4);
}

TEST(DiscoverySimulation, ThreeNodesConverge) {
  DiscoveryScenario scenario;
  scenario.ids = {3, 50, 77};
  scenario.start_s = {1000, 1010, 1100};
  scenario.coolness = 4;
  DiscoveryResult result = simulate_discovery(scenario, true);
  ASSERT_TRUE(result.converged_at_s.has_value());
  EXPECT_EQ(result.cycle_seconds, 60);
  // The trace ends two shared cycles after convergence: [3 50 77 _] or
  // with the blank third.
  const SlotTrace& last = result.trace.back();
  for (const NodeSlot& node : last.nodes) EXPECT_NE(node.action, NodeAction::kWait);
}

// The figure's rule can lock two nodes that are each the lowest id they
// know in equally long cycles (see blank_slot.h); kAnywhere frees them.
TEST(DiscoverySimulation, FigureRuleLockAndTheAnywhereRule) {
  DiscoveryScenario scenario;
  scenario.ids = {12, 90, 33};
  scenario.start_s = {1000};
  scenario.coolness = 4;
  scenario.horizon_cycles = 100;
  scenario.blank_rule = mac::BlankRule::kFigure;
  EXPECT_FALSE(simulate_discovery(scenario, false).converged_at_s.has_value());
  scenario.blank_rule = mac::BlankRule::kAnywhere;
  EXPECT_TRUE(simulate_discovery(scenario, false).converged_at_s.has_value());
}

TEST(DiscoverySimulation, SameSeedSameResult) {
  DiscoveryMonteCarloConfig config;
  config.sizes = {3};
  config.trials = 10;
  config.p_collide = {0.5};
  EXPECT_EQ(format_discovery_csv(simulate_discovery_monte_carlo(config)),
            format_discovery_csv(simulate_discovery_monte_carlo(config)));
}

}  // namespace
}  // namespace acomms::eval
