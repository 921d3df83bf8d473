#include "link/serial_transport.h"

#include <asio/serial_port.hpp>
#include <spdlog/spdlog.h>
#include <sys/ioctl.h>

#include <cerrno>
#include <cstring>

#include "link/stream_session.h"

namespace acomms::link {

struct SerialTransport::Impl : StreamSession<Impl, asio::serial_port> {
  Impl(asio::io_context& context, SerialSettings serial, RetryOptions retry)
      : StreamSession(context, "serial", serial.device, retry), settings(std::move(serial)) {}

  SerialSettings settings;

  // Opening a serial port does not block, so it happens here and now.
  void open_stream() {
    set_state(TransportState::kOpening, settings.device);
    std::error_code ec;
    stream.open(settings.device, ec);
    if (ec) return fail("cannot open: " + ec.message());
    using sp = asio::serial_port_base;
    stream.set_option(sp::baud_rate(settings.baud), ec);
    if (!ec) stream.set_option(sp::character_size(settings.data_bits), ec);
    if (!ec) stream.set_option(sp::parity(sp::parity::none), ec);
    if (!ec) stream.set_option(sp::stop_bits(sp::stop_bits::one), ec);
    if (!ec) {
      stream.set_option(sp::flow_control(settings.hardware_flow_control ? sp::flow_control::hardware
                                                                        : sp::flow_control::none),
                        ec);
    }
    if (ec) return fail("cannot set " + std::to_string(settings.baud) + " baud 8N1: " + ec.message());
    if (settings.clear_rts) clear_rts();
    spdlog::info("serial {}: open at {} baud", settings.device, settings.baud);
    opened();
  }

  // Before the first read, so no byte arrives garbled (see SerialSettings).
  void clear_rts() {
    int rts = TIOCM_RTS;
    if (::ioctl(stream.native_handle(), TIOCMBIC, &rts) == 0) {
      spdlog::info("serial {}: RTS de-asserted", settings.device);
    } else if (errno == ENOTTY || errno == EINVAL) {
      spdlog::info("serial {}: no RTS line to de-assert ({})", settings.device, std::strerror(errno));
    } else {
      spdlog::warn("serial {}: could not de-assert RTS: {}", settings.device, std::strerror(errno));
    }
  }

  void cancel_opening() {}

  static std::string read_failure(const std::error_code& ec) { return "read failed: " + ec.message(); }
};

SerialTransport::SerialTransport(asio::io_context& context, SerialSettings settings, RetryOptions retry)
    : impl_(std::make_shared<Impl>(context, std::move(settings), retry)) {}

SerialTransport::~SerialTransport() { close(); }

void SerialTransport::open(DataCallback on_data, TransportStateCallback on_state) {
  impl_->start(std::move(on_data), std::move(on_state));
}

void SerialTransport::close() { impl_->close(); }

bool SerialTransport::write(std::string_view bytes) { return impl_->write(bytes); }

TransportState SerialTransport::state() const { return impl_->state; }
const std::string& SerialTransport::device() const { return impl_->settings.device; }

}  // namespace acomms::link
