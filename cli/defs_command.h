#pragma once
// `acommsctl defs load|list`: the DCCL message definitions the daemon knows.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_defs_command(CLI::App& app, const GlobalOptions& options);

}  // namespace acomms::cli
