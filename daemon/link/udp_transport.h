#pragma once
// A UDP socket bound to a local address that sends each datagram to a fixed
// list of peers: the "udp" driver's link and the simulator's loopback
// channel between processes.
//
// UDP has no connection to lose, but the socket can fail (the interface it
// is bound to disappears); the transport then closes it and rebinds with
// exponential backoff, reporting each state change. A peer that is not
// listening is not a failure of ours: the datagram is simply lost, as it
// would be in the water.
//
// Runs on the core thread's io_context; every callback runs there.

#include <asio/io_context.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "link/transport_state.h"

namespace acomms::link {

class UdpTransport {
 public:
  // `from` is the sender's "address:port", for logs.
  using DatagramCallback = std::function<void(std::string_view datagram, const std::string& from)>;

  // `listen` and `peers` are "host:port" (listen may use port 0: any free
  // port). Throws std::invalid_argument naming the malformed address.
  UdpTransport(asio::io_context& context, const std::string& listen, const std::vector<std::string>& peers,
               RetryOptions retry = {});
  ~UdpTransport();
  UdpTransport(const UdpTransport&) = delete;
  UdpTransport& operator=(const UdpTransport&) = delete;

  // Resolves the peers, binds `listen` and starts receiving. Throws
  // DriverError naming the address when it cannot.
  void open(DatagramCallback on_datagram, TransportStateCallback on_state = nullptr);
  // Closes the socket; no callback runs after it returns.
  void close();
  // One datagram to every peer. Returns "" or the failures, each naming the
  // peer; datagrams are dropped while the socket is not open.
  std::string send_to_peers(std::string_view datagram);

  TransportState state() const;
  // The bound port (useful after listening on port 0); 0 when not open.
  uint16_t local_port() const;
  // Datagrams larger than this are truncated by the kernel: the maximum
  // UDP payload over IPv4.
  static constexpr size_t kMaxDatagram = 65507;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace acomms::link
