#include "host_ports.h"

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <asio/write.hpp>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace acomms::fake_micromodem {

PtyPort::PtyPort(asio::io_context& context, FakeMicroModem& modem) : modem_(modem), master_(context) {
  int master = -1;
  char name[256] = {};
  if (openpty(&master, &slave_, name, nullptr, nullptr) != 0) {
    throw std::runtime_error(std::string("openpty failed: ") + std::strerror(errno));
  }
  // Raw bytes: no echo, no CR/LF translation, like a serial line in raw mode.
  termios settings{};
  tcgetattr(slave_, &settings);
  cfmakeraw(&settings);
  tcsetattr(slave_, TCSANOW, &settings);
  fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);
  master_.assign(master);
  path_ = name;
  modem_.set_output([this](std::string_view bytes) { write(bytes); });
  read();
}

PtyPort::~PtyPort() {
  modem_.set_output(nullptr);
  if (slave_ >= 0) ::close(slave_);
}

void PtyPort::write(std::string_view bytes) {
  while (!bytes.empty()) {
    ssize_t n = ::write(master_.native_handle(), bytes.data(), bytes.size());
    if (n <= 0) {  // full (nobody reading) or gone: the bytes are lost
      dropped_ += bytes.size();
      return;
    }
    bytes.remove_prefix(static_cast<size_t>(n));
  }
}

void PtyPort::read() {
  master_.async_read_some(asio::buffer(buffer_), [this](const std::error_code& error, size_t n) {
    if (error == asio::error::operation_aborted) return;
    if (!error) modem_.from_host(std::string_view(buffer_.data(), n));
    read();
  });
}

TcpPort::TcpPort(asio::io_context& context, FakeMicroModem& modem, uint16_t port)
    : modem_(modem),
      acceptor_(context, asio::ip::tcp::endpoint(asio::ip::make_address("127.0.0.1"), port)) {
  modem_.set_output([this](std::string_view bytes) {
    if (!client_) return;
    std::error_code error;
    asio::write(*client_, asio::buffer(bytes.data(), bytes.size()), error);
    if (error) client_.reset();
  });
  port_ = acceptor_.local_endpoint().port();
  accept();
}

void TcpPort::unplug() {
  std::error_code ignored;
  acceptor_.close(ignored);
  if (client_) client_->close(ignored);
  client_.reset();
}

void TcpPort::plug() {
  if (acceptor_.is_open()) return;
  asio::ip::tcp::endpoint endpoint(asio::ip::make_address("127.0.0.1"), port_);
  acceptor_.open(endpoint.protocol());
  acceptor_.set_option(asio::ip::tcp::acceptor::reuse_address(true));
  acceptor_.bind(endpoint);
  acceptor_.listen();
  accept();
}

void TcpPort::accept() {
  acceptor_.async_accept([this](const std::error_code& error, asio::ip::tcp::socket socket) {
    if (error == asio::error::operation_aborted) return;
    if (!error) {
      if (client_) client_->close();  // its pending read ends, aborted
      client_ = std::make_shared<asio::ip::tcp::socket>(std::move(socket));
      read();
    }
    accept();
  });
}

void TcpPort::read() {
  std::shared_ptr<asio::ip::tcp::socket> client = client_;
  client->async_read_some(asio::buffer(buffer_), [this, client](const std::error_code& error, size_t n) {
    if (client != client_) return;  // replaced by a newer connection
    if (error) {
      client_.reset();
      return;
    }
    modem_.from_host(std::string_view(buffer_.data(), n));
    read();
  });
}

}  // namespace acomms::fake_micromodem
