#pragma once
// A TCP connection to a device server (a modem behind a serial-to-Ethernet
// gateway, a modem emulator). When the peer goes away the transport keeps
// reconnecting with exponential backoff and reports each state change, so
// the driver above sees only "bytes flow" or "waiting for the device".
//
// Runs on the core thread's io_context; every callback runs there.

#include <asio/io_context.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "link/transport_state.h"

namespace acomms::link {

class TcpClientTransport {
 public:
  using DataCallback = std::function<void(std::string_view bytes)>;

  // `address` is "host:port" (throws std::invalid_argument if malformed).
  TcpClientTransport(asio::io_context& context, const std::string& address, RetryOptions retry = {});
  ~TcpClientTransport();  // closes
  TcpClientTransport(const TcpClientTransport&) = delete;
  TcpClientTransport& operator=(const TcpClientTransport&) = delete;

  // Starts connecting; returns at once. Callbacks run on the io_context.
  void open(DataCallback on_data, TransportStateCallback on_state);
  // Disconnects; no callback runs after it returns.
  void close();
  // Queues bytes for the peer. False (bytes dropped) when not connected:
  // stale modem commands are worse than none after a reconnect.
  bool write(std::string_view bytes);

  TransportState state() const;
  const std::string& address() const;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace acomms::link
