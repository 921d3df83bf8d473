#pragma once
// `acommsctl gram depth` and `acommsctl gram env show|update`: the daemon's
// model service (acomms.v1.Gram), unlike the offline gram tl|arrivals|ssp.

#include <CLI/CLI.hpp>

#include "global_options.h"

namespace acomms::cli {

void add_gram_service_commands(CLI::App& gram, const GlobalOptions& options);

}  // namespace acomms::cli
