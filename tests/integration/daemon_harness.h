#pragma once
// Helpers for tests that run real acommsd processes: wait for the standard
// health check, and open an API stub.

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <memory>
#include <string>

#include "acomms/v1/acomms.grpc.pb.h"
#include "child_process.h"

namespace acomms::testing {

// Polls grpc.health.v1 on the unix socket until SERVING; false if the
// daemon exits or `timeout` passes first.
bool wait_serving(ChildProcess& daemon, const std::string& socket,
                  std::chrono::milliseconds timeout = std::chrono::seconds(20));

std::unique_ptr<v1::Acomms::Stub> api(const std::string& socket);

// A UDP port on 127.0.0.1 that was free a moment ago.
int free_udp_port();

}  // namespace acomms::testing
