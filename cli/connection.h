#pragma once
// How acommsctl reaches the daemon: a channel to its unix socket (or a TCP
// address, over TLS unless --insecure), checked before use so that an absent
// daemon, or a certificate either end refuses, is one clear line.

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

#include "global_options.h"

namespace acomms::cli {

// "--socket" or $ACOMMSD_SOCKET, else the packaged default.
std::string default_socket();

// The gRPC target for a socket path or a "tcp:host:port" address.
std::string target_for(const std::string& endpoint);

// Connects within --timeout; throws std::runtime_error("cannot reach
// acommsd at ...: reason") otherwise, or core::PemFileError naming a TLS
// file (--ca, --cert, --key) that cannot be used.
std::shared_ptr<grpc::Channel> connect(const GlobalOptions& options);

}  // namespace acomms::cli
