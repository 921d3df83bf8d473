#include "link/tcp_client_transport.h"

#include <asio/connect.hpp>
#include <asio/ip/tcp.hpp>
#include <spdlog/spdlog.h>

#include "link/address.h"
#include "link/stream_session.h"

namespace acomms::link {

struct TcpClientTransport::Impl : StreamSession<Impl, asio::ip::tcp::socket> {
  Impl(asio::io_context& context, const std::string& address, RetryOptions retry)
      : StreamSession(context, "tcp", address, retry), resolver(context),
        host_port(parse_host_port(address, "tcp address")) {}

  asio::ip::tcp::resolver resolver;
  HostPort host_port;

  void open_stream() {
    set_state(TransportState::kOpening, name);
    auto self = shared_from_this();
    uint64_t gen = generation;
    resolver.async_resolve(host_port.host, host_port.port,
        [self, gen](const std::error_code& ec, asio::ip::tcp::resolver::results_type results) {
          if (gen != self->generation) return;
          if (ec) return self->fail("cannot resolve: " + ec.message());
          asio::async_connect(self->stream, results,
              [self, gen](const std::error_code& ec, const asio::ip::tcp::endpoint&) {
                if (gen != self->generation) return;
                if (ec) return self->fail("cannot connect: " + ec.message());
                spdlog::info("tcp {}: connected", self->name);
                self->opened();
              });
        });
  }

  void cancel_opening() { resolver.cancel(); }

  static std::string read_failure(const std::error_code& ec) {
    return ec == asio::error::eof ? std::string("peer closed the connection") : "read failed: " + ec.message();
  }
};

TcpClientTransport::TcpClientTransport(asio::io_context& context, const std::string& address,
                                       RetryOptions retry)
    : impl_(std::make_shared<Impl>(context, address, retry)) {}

TcpClientTransport::~TcpClientTransport() { close(); }

void TcpClientTransport::open(DataCallback on_data, TransportStateCallback on_state) {
  impl_->start(std::move(on_data), std::move(on_state));
}

void TcpClientTransport::close() { impl_->close(); }

bool TcpClientTransport::write(std::string_view bytes) { return impl_->write(bytes); }

TransportState TcpClientTransport::state() const { return impl_->state; }
const std::string& TcpClientTransport::address() const { return impl_->name; }

}  // namespace acomms::link
