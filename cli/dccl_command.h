#pragma once
// `acommsctl dccl encode|decode|analyze`: the DCCL codec offline, without a
// daemon, for message designers and for checking bytes seen on a link.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_dccl_command(CLI::App& app, const GlobalOptions& options);

}  // namespace acomms::cli
