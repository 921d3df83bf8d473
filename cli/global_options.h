#pragma once
#include <string>

namespace acomms::cli {

// Options every acommsctl command shares.
struct GlobalOptions {
  std::string endpoint;    // socket path, or tcp:host:port
  double timeout_s = 3.0;  // to connect, and for each call
  bool json = false;       // machine-readable output
};

}  // namespace acomms::cli
