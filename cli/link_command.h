#pragma once
// `acommsctl link status|enable|disable|cycle|raw|ping|lbl|mini`: each of
// the node's links (its modem driver, enabled or not), the MAC's slot
// cycle, the raw link log (link_raw_command.h) and the Micro-Modem's own
// transmissions (link_extra_command.h).

#include <CLI/CLI.hpp>

#include <string>

#include "acomms/v1/config.pb.h"

namespace acomms::cli {

struct GlobalOptions;

void add_link_command(CLI::App& app, const GlobalOptions& options);

// "SRC[:DEST]@RATE/SECONDS", e.g. "2:1@1/10". Throws UsageError naming the
// slot and the syntax.
v1::MacSlot parse_slot(const std::string& text);

}  // namespace acomms::cli
