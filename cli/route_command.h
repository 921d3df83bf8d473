#pragma once
// `acommsctl route ls`: a gateway's routes (README "Gateways: routes and
// the envelope"). Thread-compatible: runs on acommsctl's one thread.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_route_command(CLI::App& app, const GlobalOptions& options);

}  // namespace acomms::cli
