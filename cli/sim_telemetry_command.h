#pragma once
// `acommsctl sim telemetry`: position telemetry on a recorded or generated
// track, every observer x model (see daemon/eval/telemetry_evaluation.h), or
// --generate auv|glider to print a generated track (daemon/eval/
// track_generator.h) as CSV.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_sim_telemetry_command(CLI::App* sim, const GlobalOptions& options);

}  // namespace acomms::cli
