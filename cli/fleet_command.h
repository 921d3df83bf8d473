#pragma once
// `acommsctl fleet ls|render|check|import`: a fleet file (README "Fleet
// configuration") offline, no daemon needed: its nodes, one node's
// flattened config (with where each field came from), the checks that
// must pass before launch, and a first fleet file made from per-node
// configs.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_fleet_command(CLI::App& app, const GlobalOptions& options);

}  // namespace acomms::cli
