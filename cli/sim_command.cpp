#include "sim_command.h"

#include <cstdint>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "comma_list.h"
#include "global_options.h"
#include "eval/discovery_monte_carlo.h"
#include "eval/discovery_report.h"
#include "eval/discovery_simulation.h"
#include "eval/market_simulation.h"
#include "mac/blank_slot.h"
#include "sim_depth_adaptation_command.h"
#include "sim_telemetry_command.h"

namespace acomms::cli {
namespace {

struct QueueMarketOptions {
  eval::MarketConfig config;
  std::vector<double> p_empty = eval::default_p_empty_grid();
};

void add_queue_market_command(CLI::App* sim) {
  static QueueMarketOptions options;
  CLI::App* market = sim->add_subcommand(
      "queue-market",
      "The queue marketplace experiment of Schneider (2013), section 2.3.4: mean total score of "
      "the dynamic priority, a fixed priority on value_base, and lowest-ttl-first, as CSV "
      "p_empty,dynamic,fixed_value,lowest_ttl");
  market->add_option("--tau-s-ratio", options.config.tau_s_ratio,
                     "R: the variety time scale tau_s = R * tau (D_s = (t - t_last) / tau_s)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  market->add_option("--trials", options.config.trials,
                     "Seeded trials per P_empty point")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  market->add_option("--seed", options.config.seed, "Random seed (same seed, same output)")
      ->capture_default_str();
  market->add_option("--p-empty", options.p_empty,
                     "P_empty values, comma-separated (default 0,0.1,...,0.9)")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 1.0));
  market->add_option("--transmissions", options.config.transmissions,
                     "N: transmissions per trial, one message each")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  market->add_option("--tau", options.config.tau_s, "tau: seconds between transmissions")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  market->footer("Example:\n  acommsctl sim queue-market --tau-s-ratio 10 --trials 200 --p-empty 0,0.5,0.9");
  market->callback([] {
    std::vector<eval::MarketPoint> points = eval::simulate_market(options.config, options.p_empty);
    std::cout << eval::format_market_csv(points) << std::flush;
  });
}


// "3-6,8" -> 3,4,5,6,8. "n+1" (when allowed) -> 0, standing for the network
// size + 1.
std::vector<int64_t> parse_int_list(const std::string& text, const std::string& option,
                                    bool allow_size_plus_one) {
  std::vector<int64_t> values;
  for (const std::string& token : split_commas(text)) {
    if (allow_size_plus_one && token == "n+1") {
      values.push_back(0);
      continue;
    }
    try {
      size_t used = 0;
      const size_t dash = token.find('-', 1);
      const int64_t low = std::stoll(token.substr(0, dash), &used);
      if (used != token.substr(0, dash).size()) throw std::invalid_argument(token);
      int64_t high = low;
      if (dash != std::string::npos) {
        high = std::stoll(token.substr(dash + 1), &used);
        if (used != token.size() - dash - 1) throw std::invalid_argument(token);
      }
      if (high < low || high - low > 10000) throw std::invalid_argument(token);
      for (int64_t v = low; v <= high; ++v) values.push_back(v);
    } catch (const std::exception&) {
      throw CLI::ValidationError(option, "'" + token + "' is not a number or a range A-B" +
                                             (allow_size_plus_one ? " or n+1" : ""));
    }
  }
  return values;
}

std::vector<double> parse_double_list(const std::string& text, const std::string& option) {
  std::vector<double> values;
  for (const std::string& token : split_commas(text)) {
    try {
      size_t used = 0;
      values.push_back(std::stod(token, &used));
      if (used != token.size()) throw std::invalid_argument(token);
    } catch (const std::exception&) {
      throw CLI::ValidationError(option, "'" + token + "' is not a number");
    }
  }
  return values;
}

struct MacDiscoveryOptions {
  std::vector<int32_t> ids;
  std::vector<double> start_s = {0};
  double slot_seconds = 15;
  std::string coolness;   // empty: ids + 1 (scenario) or n+1 (Monte Carlo)
  std::string p_collide;  // empty: 1 (scenario) or 1,0.75,0.5 (Monte Carlo)
  uint32_t expire_cycles = 5;
  uint64_t seed = 1;
  double horizon_cycles = 200;
  bool monte_carlo = false;
  std::string sizes = "3-6";
  int trials = 200;
  double start_window_cycles = 4;
  std::string blank_rule = mac::blank_rule_name(mac::kDefaultBlankRule);
};

mac::BlankRule blank_rule_of(const std::string& name) {
  if (std::optional<mac::BlankRule> rule = mac::blank_rule_from_name(name)) return *rule;
  throw CLI::ValidationError("--blank-rule", "'" + name + "': use figure, congruence or anywhere");
}

void run_mac_discovery(const MacDiscoveryOptions& options) {
  if (!options.monte_carlo) {
    if (options.ids.empty()) throw CLI::ValidationError("--ids", "needed (or --monte-carlo)");
    eval::DiscoveryScenario scenario;
    scenario.ids = options.ids;
    scenario.start_s = options.start_s;
    scenario.slot_seconds = options.slot_seconds;
    scenario.expire_cycles = options.expire_cycles;
    scenario.blank_rule = blank_rule_of(options.blank_rule);
    scenario.seed = options.seed;
    scenario.horizon_cycles = options.horizon_cycles;
    scenario.coolness = static_cast<uint32_t>(options.ids.size() + 1);
    if (!options.coolness.empty()) {
      std::vector<int64_t> c = parse_int_list(options.coolness, "--coolness", false);
      if (c.size() != 1 || c[0] < 1)
        throw CLI::ValidationError("--coolness", "one value >= 1 for a single scenario");
      scenario.coolness = static_cast<uint32_t>(c[0]);
    }
    if (!options.p_collide.empty()) {
      std::vector<double> p = parse_double_list(options.p_collide, "--p-collide");
      if (p.size() != 1) throw CLI::ValidationError("--p-collide", "one value for a single scenario");
      scenario.p_collide = p[0];
    }
    eval::DiscoveryResult result = eval::simulate_discovery(scenario, true);
    std::cout << eval::format_discovery(scenario, result) << std::flush;
    return;
  }
  eval::DiscoveryMonteCarloConfig config;
  config.sizes.clear();
  for (int64_t n : parse_int_list(options.sizes, "--sizes", false)) {
    if (n < 1 || n > 127) throw CLI::ValidationError("--sizes", "a network has 1 to 127 nodes");
    config.sizes.push_back(static_cast<int>(n));
  }
  if (!options.coolness.empty()) {
    config.coolness.clear();
    for (int64_t c : parse_int_list(options.coolness, "--coolness", true)) {
      if (c < 0) throw CLI::ValidationError("--coolness", "values must be >= 1 (or n+1)");
      config.coolness.push_back(static_cast<uint32_t>(c));
    }
  }
  if (!options.p_collide.empty()) config.p_collide = parse_double_list(options.p_collide, "--p-collide");
  for (double p : config.p_collide)
    if (!(p >= 0 && p <= 1)) throw CLI::ValidationError("--p-collide", "values must be within [0, 1]");
  config.trials = options.trials;
  config.slot_seconds = options.slot_seconds;
  config.expire_cycles = options.expire_cycles;
  config.blank_rule = blank_rule_of(options.blank_rule);
  config.start_window_cycles = options.start_window_cycles;
  config.horizon_cycles = options.horizon_cycles;
  config.seed = options.seed;
  std::cout << eval::format_discovery_csv(eval::simulate_discovery_monte_carlo(config)) << std::flush;
}

void add_mac_discovery_command(CLI::App* sim) {
  static MacDiscoveryOptions options;
  CLI::App* command = sim->add_subcommand(
      "mac-discovery",
      "The auto-discovery TDMA MAC (thesis 2.4.3) on a simulated one-hop channel: one scenario "
      "slot by slot (--ids), or a Monte Carlo over random networks as CSV "
      "nodes,coolness,p_collide,collision_prob,mean_discovery_slots,fail_pct (--monte-carlo)");
  command->add_option("--ids", options.ids, "Scenario: the nodes' modem ids, e.g. 1,2")
      ->delimiter(',')
      ->check(CLI::Range(1, 1 << 30));
  command->add_option("--start", options.start_s,
                      "Scenario: power-on, seconds since midnight UTC; one value for all nodes or "
                      "one per node (e.g. 0,20)")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--slot", options.slot_seconds, "Slot length, seconds")
      ->check(CLI::Range(0.001, 86400.0))
      ->capture_default_str();
  command->add_option("--coolness", options.coolness,
                      "C: scenario, one value (default: nodes + 1); Monte Carlo, a list of values "
                      "and ranges, n+1 meaning network size + 1 (default n+1), e.g. 1-10");
  command->add_option("--p-collide", options.p_collide,
                      "Probability that a listener loses colliding packets: scenario, one value "
                      "(default 1); Monte Carlo, a list (default 1,0.75,0.5)");
  command->add_option("--expire-cycles", options.expire_cycles,
                      "Cycles of silence after which a node is dropped")
      ->check(CLI::Range(1u, 1000000u))
      ->capture_default_str();
  command->add_option("--horizon-cycles", options.horizon_cycles,
                      "Give up this many full-network cycles after the last power-on")
      ->check(CLI::Range(1.0, 1e6))
      ->capture_default_str();
  command->add_option("--blank-rule", options.blank_rule,
                      "Blank placement (daemon/mac/blank_slot.h): anywhere (excited: a "
                      "pseudo-random slot before the last; the daemon's default too), figure "
                      "(last slot, penultimate when H(k, S) mod C == 0, Schneider (2013) Table "
                      "2.7) or congruence (the same, excited when k mod C == S mod C, as "
                      "goby-acomms)")
      ->check(CLI::IsMember({"figure", "congruence", "anywhere"}))
      ->capture_default_str();
  command->add_option("--seed", options.seed, "Random seed (same seed, same output)")
      ->capture_default_str();
  command->add_flag("--monte-carlo", options.monte_carlo, "Random networks instead of one scenario");
  command->add_option("--sizes", options.sizes, "Monte Carlo: network sizes, e.g. 3-6")
      ->capture_default_str();
  command->add_option("--trials", options.trials, "Monte Carlo: networks per point")
      ->check(CLI::Range(1, 10000000))
      ->capture_default_str();
  command->add_option("--start-window-cycles", options.start_window_cycles,
                      "Monte Carlo: power-on times spread over this many full-network cycles")
      ->check(CLI::Range(0.0, 1e4))
      ->capture_default_str();
  command->footer(
      "Examples:\n"
      "  acommsctl sim mac-discovery --ids 1,2 --slot 15 --coolness 3 --start 0 --blank-rule figure\n"
      "  acommsctl sim mac-discovery --monte-carlo --sizes 3-6 --coolness 4-7 --p-collide 1 --trials 200");
  command->callback([] {
    try {
      run_mac_discovery(options);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError("mac-discovery", e.what());
    }
  });
}

}  // namespace

CLI::App* add_sim_command(CLI::App& app, const GlobalOptions& options) {
  CLI::App* sim = app.add_subcommand("sim", "Offline simulations (no daemon needed)");
  sim->require_subcommand(1);
  sim->footer(
      "Examples:\n"
      "  acommsctl sim queue-market --trials 200\n"
      "  acommsctl sim mac-discovery --ids 1,2 --slot 15");
  add_queue_market_command(sim);
  add_mac_discovery_command(sim);
  add_sim_telemetry_command(sim, options);
  add_sim_depth_adaptation_command(sim, options);
  return sim;
}

}  // namespace acomms::cli
