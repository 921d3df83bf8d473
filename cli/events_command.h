#pragma once
// `acommsctl events`: the event log, what happened to each message.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace acomms::cli {

struct GlobalOptions;

void add_events_command(CLI::App& app, const GlobalOptions& options);

// The event kinds the log records, in a message's usual order.
const std::vector<std::string>& event_kinds();

}  // namespace acomms::cli
