#pragma once
// `acommsctl sim depth-adaptation`: the GLINT10 depth-adaptation experiment
// of Schneider (2013, §4.3) on a BELLHOP-format environment the user brings
// (daemon/eval/depth_adaptation.h): receipt probability per range bin for
// fixed depths and the adaptive strategy, and whether adaptation helped.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_sim_depth_adaptation_command(CLI::App* sim, const GlobalOptions& options);

}  // namespace acomms::cli
