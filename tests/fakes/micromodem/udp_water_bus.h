#pragma once
// Joins the Water of fake modems in separate processes on one machine.
// Each process binds a UDP port on 127.0.0.1 and names its peers' ports;
// every local transmission goes to each peer as one datagram
// (acoustic_packet.h), which the peer plays into its own Water from the
// sender's position. Chosen over a Unix socket or a hub process because
// it needs no extra process and no file-system state: a fixed list of
// ports is the whole configuration.
//
// Travel time is computed at the receiver from the datagram's arrival, so
// loopback latency (tens of microseconds) is added to it: negligible at
// scale 1, and still under a millisecond of simulated time at scale 10.
// All processes must run at the same time scale.

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>

#include <array>
#include <cstdint>
#include <vector>

#include "water.h"

namespace acomms::fake_micromodem {

class UdpWaterBus {
 public:
  UdpWaterBus(asio::io_context& context, Water& water, uint16_t port, std::vector<uint16_t> peers);
  uint16_t port() const { return socket_.local_endpoint().port(); }  // port 0: the one chosen
  void add_peer(uint16_t port);
  uint64_t refused() const { return refused_; }  // datagrams that were not fake-modem packets

 private:
  void receive();
  Water& water_;
  asio::ip::udp::socket socket_;
  std::vector<asio::ip::udp::endpoint> peers_;
  std::array<char, 65536> buffer_{};
  asio::ip::udp::endpoint sender_;
  uint64_t refused_ = 0;
};

}  // namespace acomms::fake_micromodem
