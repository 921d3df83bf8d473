#include "udp_water_bus.h"

#include <iostream>

namespace acomms::fake_micromodem {

UdpWaterBus::UdpWaterBus(asio::io_context& context, Water& water, uint16_t port,
                         std::vector<uint16_t> peers)
    : water_(water),
      socket_(context, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), port)) {
  for (uint16_t peer : peers) add_peer(peer);
  water_.set_tap([this](const WaterDatagram& datagram) {
    std::string bytes = encode(datagram);
    for (const auto& peer : peers_) {
      std::error_code ignored;  // a peer not running yet simply hears nothing
      socket_.send_to(asio::buffer(bytes), peer, 0, ignored);
    }
  });
  receive();
}

void UdpWaterBus::add_peer(uint16_t port) {
  peers_.emplace_back(asio::ip::make_address("127.0.0.1"), port);
}

void UdpWaterBus::receive() {
  socket_.async_receive_from(asio::buffer(buffer_), sender_, [this](const std::error_code& error, size_t n) {
    if (error == asio::error::operation_aborted) return;
    if (!error) {
      std::string why;
      if (auto datagram = decode_datagram(std::string_view(buffer_.data(), n), &why)) {
        water_.arrive_from_elsewhere(*datagram);
      } else {
        ++refused_;
        std::cerr << "fake_micromodem: ignored a datagram on the water bus: " << why << "\n";
      }
    }
    receive();
  });
}

}  // namespace acomms::fake_micromodem
