#pragma once
// spdlog set up for a daemon: one stderr logger (journald captures stderr
// under systemd), level from the config. libprotobuf's messages go through
// it too.
//
// Not thread-safe: it replaces spdlog's default logger, so call it before
// other threads log (acommsd does, once, at start).

#include "acomms/v1/config.pb.h"

namespace acomms::core {

void configure_logging(v1::LogLevel level);

}  // namespace acomms::core
