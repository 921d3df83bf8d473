#pragma once
// `acommsctl link raw`: the modem's own words, live.
//
// The daemon writes every chunk to and from the modem to
// <data_dir>/link-raw.log (link/raw_log.h; the micromodem driver). This
// command asks the daemon for its data dir, prints the log's last lines and
// follows it as it grows, across rotations. It reads the file directly
// rather than through a new streaming RPC: the raw log is a debugging aid
// for someone on the vehicle (or logged in to it), and the file is already
// there, bounded and complete; a remote client has `link status`.

#include <CLI/CLI.hpp>

namespace acomms::cli {

struct GlobalOptions;

// Adds `raw` under `link`.
void add_link_raw_command(CLI::App& link, const GlobalOptions& options);

}  // namespace acomms::cli
