#pragma once
// Simulated modems in several processes on one machine, in real time: each
// node sends every envelope as a UDP datagram to each peer address and
// listens on its own. Used by the "sim" driver when the config has
// sim.listen; the receiving SimDriver does the physics with its own clock.

#include <asio/io_context.hpp>

#include <string>
#include <vector>

#include "link/udp_transport.h"
#include "sim/sim_medium.h"

namespace acomms::drivers {

class LoopbackMedium final : public SimMedium {
 public:
  // Throws std::invalid_argument for a malformed address.
  LoopbackMedium(asio::io_context& context, const std::string& listen, const std::vector<std::string>& peers);

  void open(Listener listener, RawListener raw) override;
  void close() override;
  std::string send(const SimEnvelope& envelope) override;
  uint64_t garbage_received() const override { return garbage_; }
  uint16_t local_port() const { return transport_.local_port(); }

 private:
  link::UdpTransport transport_;
  std::string listen_;
  uint64_t garbage_ = 0;
};

}  // namespace acomms::drivers
