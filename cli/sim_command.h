#pragma once
// `acommsctl sim ...`: offline simulations, no daemon needed.
//   sim queue-market   the marketplace evaluation of the dynamic priority
//                      in Schneider (2013), section 2.3.4 (see
//                      daemon/eval/market_simulation.h)
//   sim mac-discovery  the auto-discovery TDMA MAC on a simulated channel
//                      (see daemon/eval/discovery_simulation.h)
//   sim telemetry      position telemetry on a track (sim_telemetry_command.h)
// Further simulations are added as subcommands of `sim` in add_sim_command.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

// Adds `sim` (a parent that requires one subcommand) with its subcommands.
// Returns `sim` so that others can hang more simulations beneath it.
CLI::App* add_sim_command(CLI::App& app, const GlobalOptions& options);

}  // namespace acomms::cli
