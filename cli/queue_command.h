#pragma once
// `acommsctl queue ls|cancel|flush|stats`: the messages waiting for the link.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_queue_command(CLI::App& app, const GlobalOptions& options);

}  // namespace acomms::cli
