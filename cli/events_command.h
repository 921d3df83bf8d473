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

// "1712345678.5" (seconds since the Unix epoch), "now", or relative to
// `now_s`: "-30s", "-10m", "-2h", "-1d". Throws UsageError.
double parse_time(const std::string& text, double now_s);

}  // namespace acomms::cli
