#pragma once
// spdlog set up for a daemon: one stderr logger (journald captures stderr
// under systemd), level from the config. libprotobuf's messages go through
// it too.

#include "acomms/v1/config.pb.h"

namespace acomms::core {

void configure_logging(v1::LogLevel level);

}  // namespace acomms::core
