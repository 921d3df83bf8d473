#include "iridium/sbd_port.h"

#include <stdexcept>

#include "link/serial_transport.h"
#include "link/tcp_client_transport.h"

namespace acomms::drivers::iridium {
namespace {

constexpr std::string_view kTcpPrefix = "tcp:";

// One class for both transports: they share open/close/write.
template <typename Transport>
class TransportPort final : public SbdPort {
 public:
  template <typename... Args>
  TransportPort(std::string name, Args&&... args) : name_(std::move(name)), transport_(std::forward<Args>(args)...) {}
  void open(DataCallback on_data, link::TransportStateCallback on_state) override {
    transport_.open(std::move(on_data), std::move(on_state));
  }
  void close() override { transport_.close(); }
  bool write(std::string_view bytes) override { return transport_.write(bytes); }
  std::string name() const override { return name_; }

 private:
  std::string name_;
  Transport transport_;
};

}  // namespace

std::unique_ptr<SbdPort> transport_port(const std::string& port, unsigned baud, bool rts_cts,
                                        asio::io_context& context) {
  if (port.empty()) {
    throw std::invalid_argument(
        "driver.iridium.port is empty: give the modem's serial device (\"/dev/ttyUSB0\") or \"tcp:HOST:PORT\"");
  }
  if (port.starts_with(kTcpPrefix)) {
    std::string address = port.substr(kTcpPrefix.size());
    if (address.find(':') == std::string::npos) {
      throw std::invalid_argument("driver.iridium.port \"" + port + "\": expected tcp:HOST:PORT");
    }
    return std::make_unique<TransportPort<link::TcpClientTransport>>(port, context, address);
  }
  link::SerialSettings settings;
  settings.device = port;
  settings.baud = baud == 0 ? 19200 : baud;  // the 9602/9603 power-up rate (spec §1)
  settings.hardware_flow_control = rts_cts;
  return std::make_unique<TransportPort<link::SerialTransport>>(port, context, settings);
}

}  // namespace acomms::drivers::iridium
