#pragma once
// Helpers for tests that run real sockets on an io_context: bounded waits.

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>

#include <chrono>
#include <functional>

namespace acomms::link::testing {

// Runs `io` until `done()` or `timeout`; returns done().
inline bool run_until(asio::io_context& io, const std::function<bool()>& done,
                      std::chrono::milliseconds timeout = std::chrono::seconds(3)) {
  auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done() && std::chrono::steady_clock::now() < deadline) {
    if (io.stopped()) io.restart();
    io.run_one_for(std::chrono::milliseconds(10));
  }
  return done();
}

// A UDP port that was free a moment ago on 127.0.0.1.
inline unsigned short free_udp_port() {
  asio::io_context io;
  asio::ip::udp::socket socket(io, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  return socket.local_endpoint().port();
}

}  // namespace acomms::link::testing
