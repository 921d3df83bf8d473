#pragma once
// `acommsctl geov serve`: the operator's map of the fleet, in a browser and
// in Google Earth (cli/geov/ holds the pieces; map_site.h lists the pages).

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_geov_command(CLI::App& app, const GlobalOptions& options);

}  // namespace acomms::cli
