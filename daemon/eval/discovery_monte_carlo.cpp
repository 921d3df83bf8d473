// The discovery Monte Carlo: many random networks (ids, power-on times,
// channel streams) per network size, each run as one scenario
// (discovery_simulation.cpp) for every coolness and p_collide asked for,
// pooled into one point per combination. Trial j of a size draws the same
// network for every combination (common random numbers), so the points
// differ by the parameters, not by luck; the draws are defined in
// discovery_monte_carlo.h.
#include "eval/discovery_monte_carlo.h"

#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <utility>

#include "eval/discovery_simulation.h"
#include "util/splitmix64.h"

namespace acomms::eval {
namespace {

using util::SplitMix64;

constexpr int32_t kMaxModemId = 127;  // 7-bit modem ids, 0 being broadcast

struct Network {
  std::vector<int32_t> ids;
  std::vector<double> start_s;
  uint64_t channel_seed = 0;
};

Network draw_network(const DiscoveryMonteCarloConfig& config, int nodes, int trial) {
  SplitMix64 random(config.seed * 0x100000001b3ULL ^ (static_cast<uint64_t>(nodes) << 40) ^
                    static_cast<uint64_t>(trial));
  random.next();
  Network network;
  std::set<int32_t> ids;
  while (static_cast<int>(ids.size()) < nodes)
    ids.insert(1 + static_cast<int32_t>(random.below(kMaxModemId)));
  network.ids.assign(ids.begin(), ids.end());
  // Shuffled, so that power-on order is not id order.
  for (size_t i = network.ids.size(); i > 1; --i)
    std::swap(network.ids[i - 1], network.ids[random.below(i)]);
  const double cycle = config.slot_seconds * (nodes + 1);
  const double window = config.start_window_cycles * cycle;
  const double room = 86400 - window - (config.horizon_cycles + 3) * cycle;
  const double base = room > 0 ? std::floor(random.uniform() * room) : 0;
  for (int i = 0; i < nodes; ++i)
    network.start_s.push_back(base + std::round(random.uniform() * window * 1e3) / 1e3);
  network.channel_seed = random.next();
  return network;
}

}  // namespace

std::vector<DiscoveryPoint> simulate_discovery_monte_carlo(const DiscoveryMonteCarloConfig& config) {
  if (config.trials < 1) throw std::invalid_argument("--trials must be >= 1");
  for (int nodes : config.sizes)
    if (nodes < 1 || nodes > kMaxModemId)
      throw std::invalid_argument("--sizes: a network has 1 to 127 nodes");
  std::vector<DiscoveryPoint> points;
  for (int nodes : config.sizes) {
    std::vector<Network> networks;
    for (int j = 0; j < config.trials; ++j) networks.push_back(draw_network(config, nodes, j));
    for (uint32_t coolness_choice : config.coolness) {
      const uint32_t coolness = coolness_choice == 0 ? static_cast<uint32_t>(nodes + 1) : coolness_choice;
      for (double p_collide : config.p_collide) {
        int64_t transmissions = 0, collided = 0, converged = 0;
        double slots_total = 0;
        for (const Network& network : networks) {
          DiscoveryScenario scenario;
          scenario.ids = network.ids;
          scenario.start_s = network.start_s;
          scenario.slot_seconds = config.slot_seconds;
          scenario.coolness = coolness;
          scenario.expire_cycles = config.expire_cycles;
          scenario.blank_rule = config.blank_rule;
          scenario.p_collide = p_collide;
          scenario.seed = network.channel_seed;
          scenario.horizon_cycles = config.horizon_cycles;
          DiscoveryResult result = simulate_discovery(scenario, false);
          transmissions += result.transmissions;
          collided += result.collided_transmissions;
          if (result.converged_at_s) {
            ++converged;
            slots_total += (*result.converged_at_s - result.last_start_s) / config.slot_seconds;
          }
        }
        DiscoveryPoint point;
        point.nodes = nodes;
        point.coolness = coolness;
        point.p_collide = p_collide;
        point.collision_prob =
            transmissions ? static_cast<double>(collided) / static_cast<double>(transmissions) : 0;
        point.mean_discovery_slots =
            converged ? slots_total / static_cast<double>(converged) : std::nan("");
        point.fail_pct = 100.0 * static_cast<double>(config.trials - converged) / config.trials;
        points.push_back(point);
      }
    }
  }
  return points;
}

}  // namespace acomms::eval
