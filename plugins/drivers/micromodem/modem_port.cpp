#include "micromodem/modem_port.h"

#include <stdexcept>

#include "link/serial_transport.h"
#include "link/tcp_client_transport.h"

namespace acomms::drivers::micromodem {
namespace {

constexpr std::string_view kTcpPrefix = "tcp:";

class SerialPort final : public ModemPort {
 public:
  SerialPort(asio::io_context& context, link::SerialSettings settings)
      : transport_(context, std::move(settings)) {}
  void open(DataCallback on_data, link::TransportStateCallback on_state) override {
    transport_.open(std::move(on_data), std::move(on_state));
  }
  void close() override { transport_.close(); }
  bool write(std::string_view bytes) override { return transport_.write(bytes); }
  std::string name() const override { return transport_.device(); }

 private:
  link::SerialTransport transport_;
};

class TcpPort final : public ModemPort {
 public:
  TcpPort(asio::io_context& context, const std::string& address) : transport_(context, address) {}
  void open(DataCallback on_data, link::TransportStateCallback on_state) override {
    transport_.open(std::move(on_data), std::move(on_state));
  }
  void close() override { transport_.close(); }
  bool write(std::string_view bytes) override { return transport_.write(bytes); }
  std::string name() const override { return "tcp:" + transport_.address(); }

 private:
  link::TcpClientTransport transport_;
};

}  // namespace

std::unique_ptr<ModemPort> transport_port(const std::string& port, unsigned baud, asio::io_context& context) {
  if (port.empty()) {
    throw std::invalid_argument(
        "driver.micromodem.port is empty: give the modem's serial device (\"/dev/ttyUSB0\") or \"tcp:HOST:PORT\"");
  }
  if (port.starts_with(kTcpPrefix)) {
    std::string address = port.substr(kTcpPrefix.size());
    if (address.find(':') == std::string::npos) {
      throw std::invalid_argument("driver.micromodem.port \"" + port + "\": expected tcp:HOST:PORT");
    }
    return std::make_unique<TcpPort>(context, address);
  }
  link::SerialSettings settings;
  settings.device = port;
  settings.baud = baud == 0 ? 19200 : baud;
  // MM2 garbles its output while RTS is asserted (spec §1, §10 quirk 12).
  // Which modem it is shows only after the port is open, and an MM1 with
  // flow control off (the driver never turns it on) ignores RTS: so always.
  settings.clear_rts = true;
  return std::make_unique<SerialPort>(context, settings);
}

}  // namespace acomms::drivers::micromodem
