#include "tcp_modem_host.h"

#include <asio/ip/tcp.hpp>
#include <asio/post.hpp>
#include <asio/write.hpp>

#include <array>
#include <future>
#include <thread>

#include "core/clock.h"
#include "core/scheduler.h"

namespace acomms::fake_iridium {

using asio::ip::tcp;

struct TcpModemHost::Impl {
  Impl(SbdGateway& gateway, FakeSbdConfig config)
      : acceptor(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)),
        scheduler(io, clock),
        modem(scheduler, gateway, std::move(config)) {
    modem.set_output([this](std::string_view bytes) {
      if (!socket || !socket->is_open()) return;  // a modem talking to no one
      auto data = std::make_shared<std::string>(bytes);
      auto keep = socket;
      asio::async_write(*socket, asio::buffer(*data), [data, keep](const std::error_code&, size_t) {});
    });
    accept();
    thread = std::thread([this] { io.run(); });
  }
  ~Impl() {
    asio::post(io, [this] {
      std::error_code ignored;
      acceptor.close(ignored);
      if (socket) socket->close(ignored);
      io.stop();
    });
    thread.join();
  }

  void accept() {
    acceptor.async_accept([this](const std::error_code& ec, tcp::socket peer) {
      if (ec) return;
      if (socket) {
        std::error_code ignored;
        socket->close(ignored);
      }
      socket = std::make_shared<tcp::socket>(std::move(peer));
      read(socket);
      accept();
    });
  }

  void read(std::shared_ptr<tcp::socket> s) {
    s->async_read_some(asio::buffer(buffer), [this, s](const std::error_code& ec, size_t n) {
      if (ec || s != socket) return;
      modem.from_host(std::string_view(buffer.data(), n));
      read(s);
    });
  }

  asio::io_context io;
  tcp::acceptor acceptor;
  core::SystemClock clock;
  core::AsioScheduler scheduler;
  FakeSbdModem modem;
  std::shared_ptr<tcp::socket> socket;
  std::array<char, 1024> buffer{};
  std::thread thread;
};

TcpModemHost::TcpModemHost(SbdGateway& gateway, FakeSbdConfig config)
    : impl_(std::make_unique<Impl>(gateway, std::move(config))) {}

TcpModemHost::~TcpModemHost() = default;

int TcpModemHost::port() const { return impl_->acceptor.local_endpoint().port(); }

void TcpModemHost::call(const std::function<void(FakeSbdModem& modem)>& work) {
  std::promise<void> done;
  asio::post(impl_->io, [&] {
    work(impl_->modem);
    done.set_value();
  });
  done.get_future().wait();
}

std::string TcpModemHost::transcript() {
  std::string out;
  call([&out](FakeSbdModem& modem) { out = modem.transcript(); });
  return out;
}

}  // namespace acomms::fake_iridium
