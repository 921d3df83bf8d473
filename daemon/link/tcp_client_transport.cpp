#include "link/tcp_client_transport.h"

#include <asio/connect.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/steady_timer.hpp>
#include <asio/write.hpp>
#include <spdlog/spdlog.h>

#include <array>
#include <deque>

#include "link/address.h"
#include "link/backoff.h"

namespace acomms::link {

// Handlers hold a shared_ptr to the Impl, so an operation that completes
// after close() (with operation_aborted) never touches freed memory; the
// generation number tells stale handlers from current ones.
struct TcpClientTransport::Impl : std::enable_shared_from_this<Impl> {
  Impl(asio::io_context& context, std::string address, RetryOptions retry)
      : resolver(context), socket(context), timer(context), address(std::move(address)),
        backoff(retry.min_s, retry.max_s) {}

  asio::ip::tcp::resolver resolver;
  asio::ip::tcp::socket socket;
  asio::steady_timer timer;
  std::string address;
  HostPort host_port;
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

  void connect() {
    set_state(TransportState::kOpening, address);
    auto self = shared_from_this();
    uint64_t gen = generation;
    resolver.async_resolve(host_port.host, host_port.port,
        [self, gen](const std::error_code& ec, asio::ip::tcp::resolver::results_type results) {
          if (gen != self->generation) return;
          if (ec) return self->fail("cannot resolve: " + ec.message());
          asio::async_connect(self->socket, results,
              [self, gen](const std::error_code& ec, const asio::ip::tcp::endpoint&) {
                if (gen != self->generation) return;
                if (ec) return self->fail("cannot connect: " + ec.message());
                self->backoff.reset();
                spdlog::info("tcp {}: connected", self->address);
                self->set_state(TransportState::kOpen, self->address);
                self->read();
              });
        });
  }

  void read() {
    auto self = shared_from_this();
    uint64_t gen = generation;
    socket.async_read_some(asio::buffer(buffer), [self, gen](const std::error_code& ec, size_t n) {
      if (gen != self->generation) return;
      if (ec) {
        return self->fail(ec == asio::error::eof ? std::string("peer closed the connection")
                                                 : "read failed: " + ec.message());
      }
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
    asio::async_write(socket, asio::buffer(*bytes), [self, gen, bytes](const std::error_code& ec, size_t) {
      if (gen != self->generation) return;
      self->writing = false;
      if (ec) return self->fail("write failed: " + ec.message());
      self->flush();
    });
  }

  void fail(const std::string& why) {
    ++generation;  // whatever is still in flight belongs to the old connection
    std::error_code ignored;
    socket.close(ignored);
    outbox.clear();
    writing = false;
    auto delay = backoff.next();
    std::string detail = address + ": " + why + "; retrying in " + format_seconds(delay);
    spdlog::warn("tcp {}", detail);
    set_state(TransportState::kWaiting, detail);
    auto self = shared_from_this();
    uint64_t gen = generation;
    timer.expires_after(delay);
    timer.async_wait([self, gen](const std::error_code& ec) {
      if (ec || gen != self->generation) return;
      self->connect();
    });
  }

  void close() {
    ++generation;
    std::error_code ignored;
    resolver.cancel();
    timer.cancel();
    socket.close(ignored);
    outbox.clear();
    writing = false;
    // No state callback: the owner asked for this, and may be mid-destruction.
    state = TransportState::kClosed;
    on_data = nullptr;
    on_state = nullptr;
  }
};

TcpClientTransport::TcpClientTransport(asio::io_context& context, const std::string& address,
                                       RetryOptions retry)
    : impl_(std::make_shared<Impl>(context, address, retry)) {
  impl_->host_port = parse_host_port(address, "tcp address");
}

TcpClientTransport::~TcpClientTransport() { close(); }

void TcpClientTransport::open(DataCallback on_data, TransportStateCallback on_state) {
  impl_->close();
  impl_->on_data = std::move(on_data);
  impl_->on_state = std::move(on_state);
  impl_->backoff.reset();
  impl_->connect();
}

void TcpClientTransport::close() { impl_->close(); }

bool TcpClientTransport::write(std::string_view bytes) {
  if (impl_->state != TransportState::kOpen) return false;
  impl_->outbox.emplace_back(bytes);
  impl_->flush();
  return true;
}

TransportState TcpClientTransport::state() const { return impl_->state; }
const std::string& TcpClientTransport::address() const { return impl_->address; }

}  // namespace acomms::link
