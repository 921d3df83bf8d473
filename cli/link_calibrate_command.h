#pragma once
// acommsctl link calibrate: the link physics fitted from this node's event
// log (eval/link_calibration.h).
//
// Decision: the fit runs here, in acommsctl, on the "packet" events the
// Events RPC returns, not in the daemon: it is an occasional, offline
// question about history the daemon already serves, it needs no core-thread
// state, and a pure module (eval/link_calibration) keeps it testable
// without a daemon. The daemon's only part is to log each packet with its
// measured and predicted SNR (link/link_controller.cpp).
//
// Thread-safety: runs on acommsctl's one thread.
#include <CLI/CLI.hpp>

#include "global_options.h"

namespace acomms::cli {

void add_link_calibrate_command(CLI::App& link, const GlobalOptions& global);

}  // namespace acomms::cli
