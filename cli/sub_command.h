#pragma once
// `acommsctl sub [TYPE...]`: follow the messages the link receives, one JSON
// line each, until interrupted.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_sub_command(CLI::App& app, const GlobalOptions& options);

}  // namespace acomms::cli
