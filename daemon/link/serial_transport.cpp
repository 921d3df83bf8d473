#include "link/serial_transport.h"

#include <asio/serial_port.hpp>
#include <asio/steady_timer.hpp>
#include <asio/write.hpp>
#include <spdlog/spdlog.h>

#include <array>
#include <deque>

#include "link/backoff.h"

namespace acomms::link {

// Same pattern as TcpClientTransport: handlers keep the Impl alive, and a
// generation number marks those that belong to a port since closed.
struct SerialTransport::Impl : std::enable_shared_from_this<Impl> {
  Impl(asio::io_context& context, SerialSettings settings, RetryOptions retry)
      : port(context), timer(context), settings(std::move(settings)), backoff(retry.min_s, retry.max_s) {}

  asio::serial_port port;
  asio::steady_timer timer;
  SerialSettings settings;
  Backoff backoff;
  DataCallback on_data;
  TransportStateCallback on_state;
  TransportState state = TransportState::kClosed;
  uint64_t generation = 0;
  std::array<char, 4096> buffer{};
  std::deque<std::string> outbox;
  bool writing = false;

  void set_state(TransportState s, const std::string& detail) {
    state = s;
    if (on_state) on_state(s, detail);
  }

  void try_open() {
    set_state(TransportState::kOpening, settings.device);
    std::error_code ec;
    port.open(settings.device, ec);
    if (ec) return fail("cannot open: " + ec.message());
    using sp = asio::serial_port_base;
    port.set_option(sp::baud_rate(settings.baud), ec);
    if (!ec) port.set_option(sp::character_size(settings.data_bits), ec);
    if (!ec) port.set_option(sp::parity(sp::parity::none), ec);
    if (!ec) port.set_option(sp::stop_bits(sp::stop_bits::one), ec);
    if (!ec) {
      port.set_option(sp::flow_control(settings.hardware_flow_control ? sp::flow_control::hardware
                                                                      : sp::flow_control::none),
                      ec);
    }
    if (ec) return fail("cannot set " + std::to_string(settings.baud) + " baud 8N1: " + ec.message());
    backoff.reset();
    spdlog::info("serial {}: open at {} baud", settings.device, settings.baud);
    set_state(TransportState::kOpen, settings.device);
    read();
  }

  void read() {
    auto self = shared_from_this();
    uint64_t gen = generation;
    port.async_read_some(asio::buffer(buffer), [self, gen](const std::error_code& ec, size_t n) {
      if (gen != self->generation) return;
      if (ec) return self->fail("read failed: " + ec.message());
      if (self->on_data) self->on_data(std::string_view(self->buffer.data(), n));
      if (gen == self->generation) self->read();
    });
  }

  void flush() {
    if (writing || outbox.empty() || state != TransportState::kOpen) return;
    // The handler owns the bytes, so close() may drop the outbox at any time.
    auto bytes = std::make_shared<std::string>(std::move(outbox.front()));
    outbox.pop_front();
    writing = true;
    auto self = shared_from_this();
    uint64_t gen = generation;
    asio::async_write(port, asio::buffer(*bytes), [self, gen, bytes](const std::error_code& ec, size_t) {
      if (gen != self->generation) return;
      self->writing = false;
      if (ec) return self->fail("write failed: " + ec.message());
      self->flush();
    });
  }

  void fail(const std::string& why) {
    ++generation;
    std::error_code ignored;
    port.close(ignored);
    outbox.clear();
    writing = false;
    auto delay = backoff.next();
    std::string detail = settings.device + ": " + why + "; retrying in " + format_seconds(delay);
    spdlog::warn("serial {}", detail);
    set_state(TransportState::kWaiting, detail);
    auto self = shared_from_this();
    uint64_t gen = generation;
    timer.expires_after(delay);
    timer.async_wait([self, gen](const std::error_code& ec) {
      if (ec || gen != self->generation) return;
      self->try_open();
    });
  }

  void close() {
    ++generation;
    std::error_code ignored;
    timer.cancel();
    port.close(ignored);
    outbox.clear();
    writing = false;
    state = TransportState::kClosed;  // no callback: the owner asked for it
    on_data = nullptr;
    on_state = nullptr;
  }
};

SerialTransport::SerialTransport(asio::io_context& context, SerialSettings settings, RetryOptions retry)
    : impl_(std::make_shared<Impl>(context, std::move(settings), retry)) {}

SerialTransport::~SerialTransport() { close(); }

void SerialTransport::open(DataCallback on_data, TransportStateCallback on_state) {
  impl_->close();
  impl_->on_data = std::move(on_data);
  impl_->on_state = std::move(on_state);
  impl_->backoff.reset();
  impl_->try_open();
}

void SerialTransport::close() { impl_->close(); }

bool SerialTransport::write(std::string_view bytes) {
  if (impl_->state != TransportState::kOpen) return false;
  impl_->outbox.emplace_back(bytes);
  impl_->flush();
  return true;
}

TransportState SerialTransport::state() const { return impl_->state; }
const std::string& SerialTransport::device() const { return impl_->settings.device; }

}  // namespace acomms::link
