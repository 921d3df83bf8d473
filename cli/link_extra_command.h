#pragma once
// `acommsctl link ping|lbl|mini`: the Micro-Modem's own transmissions
// (api/proto/acomms/drivers/micromodem_transmission.proto) through the one
// generic call, Acomms.DriverSpecific. Each waits for this node's slot (or
// a poll) before it goes out, so each has its own --wait (default 60 s)
// instead of the global --timeout.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

void add_link_extra_commands(CLI::App& link, const GlobalOptions& options);

}  // namespace acomms::cli
