#pragma once
#include <string>

namespace acomms::cli {

// Options every acommsctl command shares.
struct GlobalOptions {
  std::string endpoint;    // socket path, or tcp:host:port
  double timeout_s = 3.0;  // to connect, and for each call
  bool json = false;       // machine-readable output
  // TCP only (the unix socket is guarded by its file mode):
  std::string ca_file;    // CAs that may issue the daemon's certificate
  std::string cert_file;  // this client's certificate, for mutual TLS
  std::string key_file;   // its private key
  bool insecure = false;  // plaintext, for a daemon with grpc.insecure_tcp
};

}  // namespace acomms::cli
