#include "sim_command.h"

#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include "global_options.h"
#include "queue/market_simulation.h"

namespace acomms::cli {
namespace {

struct QueueMarketOptions {
  queue::MarketConfig config;
  std::vector<double> p_empty = queue::default_p_empty_grid();
};

void add_queue_market_command(CLI::App* sim) {
  static QueueMarketOptions options;
  CLI::App* market = sim->add_subcommand(
      "queue-market",
      "The seed's queue marketplace experiment (thesis 2.3.4): mean total score of the dynamic "
      "priority, a fixed priority on value_base, and lowest-ttl-first, as CSV "
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
  market->callback([] {
    std::vector<queue::MarketPoint> points = queue::simulate_market(options.config, options.p_empty);
    std::cout << queue::format_market_csv(points) << std::flush;
  });
}

}  // namespace

CLI::App* add_sim_command(CLI::App& app, const GlobalOptions&) {
  CLI::App* sim = app.add_subcommand("sim", "Offline simulations (no daemon needed)");
  sim->require_subcommand(1);
  add_queue_market_command(sim);
  return sim;
}

}  // namespace acomms::cli
