#include "eval/market_simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "queue/priority.h"
#include "util/splitmix64.h"

namespace acomms::eval {
namespace {

using util::SplitMix64;

uint64_t trial_seed(uint64_t seed, int trial) {
  SplitMix64 mix(seed ^ (0xD1B54A32D192ED03ULL * (static_cast<uint64_t>(trial) + 1)));
  return mix.next();
}

enum class Policy { kDynamic, kFixedValue, kLowestTtl };
constexpr int kPolicies = 3;

// The random draws of one trial, shared by every policy and P_empty.
struct Scenario {
  size_t types = 0;
  std::vector<double> occupancy;  // [k * types + i]: queue i non-empty at k iff >= P_empty
  std::vector<double> age_s;      // [k * types + i]: age of queue i's message at k
};

bool nearly_equal(double a, double b) {
  return std::fabs(a - b) <= 1e-9 * std::max(std::fabs(a), std::fabs(b));
}

// Index of the queue `policy` sends from, or -1 when all are empty.
int choose(Policy policy, const std::vector<MarketMessageType>& types,
           const std::vector<char>& non_empty,
           const std::vector<double>& last_sent, double t) {
  int best = -1;
  double best_priority = 0;
  for (size_t i = 0; i < types.size(); ++i) {
    if (!non_empty[i]) continue;
    int candidate = static_cast<int>(i);
    if (best < 0) {
      best = candidate;
      best_priority = queue::dynamic_priority(types[i].value_base, types[i].ttl_s, t - last_sent[i]);
      continue;
    }
    const MarketMessageType& a = types[i];
    const MarketMessageType& b = types[best];
    bool better = false;  // on a full tie the earlier type (best) stays
    switch (policy) {
      case Policy::kDynamic: {
        double priority = queue::dynamic_priority(a.value_base, a.ttl_s, t - last_sent[i]);
        if (nearly_equal(priority, best_priority)) {
          better = last_sent[i] < last_sent[best];
        } else {
          better = priority > best_priority;
        }
        if (better) best_priority = priority;
        break;
      }
      case Policy::kFixedValue:
        better = a.value_base > b.value_base ||
                 (a.value_base == b.value_base && a.ttl_s < b.ttl_s);
        break;
      case Policy::kLowestTtl:
        better = a.ttl_s < b.ttl_s || (a.ttl_s == b.ttl_s && a.value_base > b.value_base);
        break;
    }
    if (better) best = candidate;
  }
  return best;
}

// Total score of one trial under one policy.
double run_trial(Policy policy, const MarketConfig& config, const Scenario& scenario,
                 double p_empty) {
  const size_t n_types = config.types.size();
  const double tau_s_variety = config.tau_s_ratio * config.tau_s;
  // Lossless link: a queue's last send is its type's last reception.
  std::vector<double> last(n_types, 0.0);
  std::vector<char> non_empty(n_types);
  double total = 0;
  for (int k = 1; k <= config.transmissions; ++k) {
    const double t = k * config.tau_s;
    const size_t row = static_cast<size_t>(k - 1) * n_types;
    bool any = false;
    for (size_t i = 0; i < n_types; ++i) {
      non_empty[i] = scenario.occupancy[row + i] >= p_empty;
      any = any || non_empty[i];
    }
    if (!any) continue;
    int sent = choose(policy, config.types, non_empty, last, t);
    const MarketMessageType& type = config.types[sent];
    double d_b = type.value_base;
    double d_s = (t - last[sent]) / tau_s_variety;
    double d_e = scenario.age_s[row + sent] / type.ttl_s;
    total += d_b + d_s - d_e;
    last[sent] = t;
  }
  return total;
}

void validate(const MarketConfig& config, const std::vector<double>& p_empty) {
  if (config.types.empty()) throw std::invalid_argument("market: no message types");
  for (const auto& type : config.types) {
    if (!(type.ttl_s > 0)) throw std::invalid_argument("market: ttl must be > 0");
    if (!(type.value_base >= 0)) throw std::invalid_argument("market: value_base must be >= 0");
  }
  if (config.transmissions < 1) throw std::invalid_argument("market: transmissions must be >= 1");
  if (!(config.tau_s > 0) || !std::isfinite(config.tau_s)) {
    throw std::invalid_argument("market: tau must be > 0");
  }
  if (!(config.tau_s_ratio > 0) || !std::isfinite(config.tau_s_ratio)) {
    throw std::invalid_argument("market: tau-s-ratio must be > 0");
  }
  if (config.trials < 1) throw std::invalid_argument("market: trials must be >= 1");
  for (double p : p_empty) {
    if (!(p >= 0 && p <= 1)) throw std::invalid_argument("market: P_empty must be in [0, 1]");
  }
}

}  // namespace

std::vector<MarketMessageType> schneider2013_market_types() {
  return {{1, 1000}, {2, 2000}, {1, 3000}};
}

std::vector<double> default_p_empty_grid() {
  std::vector<double> grid;
  for (int i = 0; i < 10; ++i) grid.push_back(i / 10.0);
  return grid;
}

std::vector<MarketPoint> simulate_market(const MarketConfig& config,
                                         const std::vector<double>& p_empty) {
  validate(config, p_empty);
  const size_t n_types = config.types.size();
  const size_t cells = static_cast<size_t>(config.transmissions) * n_types;
  // sums[point * kPolicies + policy]
  std::vector<double> sums(p_empty.size() * kPolicies, 0.0);
  Scenario scenario;
  scenario.types = n_types;
  scenario.occupancy.resize(cells);
  scenario.age_s.resize(cells);
  for (int trial = 0; trial < config.trials; ++trial) {
    SplitMix64 rng(trial_seed(config.seed, trial));
    for (size_t c = 0; c < cells; ++c) {
      scenario.occupancy[c] = rng.uniform();
      scenario.age_s[c] = rng.uniform() * config.tau_s;
    }
    for (size_t point = 0; point < p_empty.size(); ++point) {
      for (int policy = 0; policy < kPolicies; ++policy) {
        sums[point * kPolicies + policy] +=
            run_trial(static_cast<Policy>(policy), config, scenario, p_empty[point]);
      }
    }
  }
  std::vector<MarketPoint> points;
  points.reserve(p_empty.size());
  for (size_t point = 0; point < p_empty.size(); ++point) {
    MarketPoint result;
    result.p_empty = p_empty[point];
    result.dynamic = sums[point * kPolicies + 0] / config.trials;
    result.fixed_value = sums[point * kPolicies + 1] / config.trials;
    result.lowest_ttl = sums[point * kPolicies + 2] / config.trials;
    points.push_back(result);
  }
  return points;
}

std::string format_market_csv(const std::vector<MarketPoint>& points) {
  std::string out = "p_empty,dynamic,fixed_value,lowest_ttl\n";
  char line[160];
  for (const auto& p : points) {
    std::snprintf(line, sizeof line, "%.6g,%.4f,%.4f,%.4f\n", p.p_empty, p.dynamic,
                  p.fixed_value, p.lowest_ttl);
    out += line;
  }
  return out;
}

}  // namespace acomms::eval
