#pragma once
// Helpers for tests that run real acommsd processes: wait for the standard
// health check or another observable event, and open an API stub.
//
// A test never sleeps to let another process get somewhere: it waits for the
// event that shows it got there (a status, a log line, a connection), with a
// bound after which the test fails and says what it waited for.

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>

#include "acomms/v1/acomms.grpc.pb.h"
#include "child_process.h"
#include "daemon_config.h"
#include "temp_dir.h"
#include "wait_until.h"  // wait_until, for every test that waits on a daemon

namespace acomms::testing {

// The connections accepted on the unix socket at `socket`, by inode (the
// accepted ends carry the listening socket's path in /proc/net/unix).
std::set<uint64_t> unix_connections(const std::string& socket);

// Waits until a connection to `socket` that is not in `before` is open,
// i.e. `client`, started after `before` was taken, has reached the daemon.
// False if the client exits or `timeout` passes first.
bool wait_connected(ChildProcess& client, const std::string& socket, const std::set<uint64_t>& before,
                    std::chrono::milliseconds timeout = std::chrono::seconds(20));

// Polls grpc.health.v1 on the unix socket until SERVING; false if the
// daemon exits or `timeout` passes first.
bool wait_serving(ChildProcess& daemon, const std::string& socket,
                  std::chrono::milliseconds timeout = std::chrono::seconds(20));

std::unique_ptr<v1::Acomms::Stub> api(const std::string& socket);

// A UDP port on 127.0.0.1 that was free a moment ago.
int free_udp_port();

// A TCP port on 127.0.0.1 that was free a moment ago.
int free_tcp_port();

// A UDP socket bound to 127.0.0.1:`port` (the test owns it and closes it),
// e.g. to hold a port a daemon's udp driver wants, or to listen as a peer.
// A bind that fails is a test failure.
int bound_udp_socket(int port);

}  // namespace acomms::testing
