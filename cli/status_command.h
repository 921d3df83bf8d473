#pragma once
// `acommsctl status`: what the daemon is and how it is configured.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_status_command(CLI::App& app, const GlobalOptions& options);

}  // namespace acomms::cli
