#pragma once
// `acommsctl send TYPE field=value ...`: queue a message for the link.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_send_command(CLI::App& app, const GlobalOptions& options);

}  // namespace acomms::cli
