#pragma once
// How acommsctl reaches the daemon: a channel to its unix socket (or a TCP
// address), checked before use so that an absent daemon is one clear line.

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

namespace acomms::cli {

// "--socket" or $ACOMMSD_SOCKET, else the packaged default.
std::string default_socket();

// The gRPC target for a socket path or a "tcp:host:port" address.
std::string target_for(const std::string& endpoint);

// Connects within `timeout_s`; throws std::runtime_error("cannot reach
// acommsd at ...: reason") otherwise.
std::shared_ptr<grpc::Channel> connect(const std::string& endpoint, double timeout_s);

}  // namespace acomms::cli
