#include "link/tcp_client_transport.h"

#include <gtest/gtest.h>

#include <asio/ip/tcp.hpp>
#include <asio/read.hpp>
#include <asio/write.hpp>

#include <memory>
#include <vector>

#include "test_io.h"

namespace acomms::link {
namespace {

using testing::run_until;

// A device server on 127.0.0.1 that can go away and come back on its port.
class Server {
 public:
  explicit Server(asio::io_context& io, unsigned short port = 0) : io_(io) { listen(port); }
  void listen(unsigned short port) {
    acceptor_ = std::make_unique<asio::ip::tcp::acceptor>(io_);
    asio::ip::tcp::endpoint endpoint(asio::ip::make_address("127.0.0.1"), port);
    acceptor_->open(endpoint.protocol());
    acceptor_->set_option(asio::socket_base::reuse_address(true));
    acceptor_->bind(endpoint);
    acceptor_->listen();
    port_ = acceptor_->local_endpoint().port();
    acceptor_->async_accept([this](const std::error_code& ec, asio::ip::tcp::socket socket) {
      if (!ec) client_ = std::make_unique<asio::ip::tcp::socket>(std::move(socket));
    });
  }
  void go_away() {
    client_.reset();
    acceptor_.reset();
  }
  unsigned short port() const { return port_; }
  asio::ip::tcp::socket* client() { return client_.get(); }

 private:
  asio::io_context& io_;
  std::unique_ptr<asio::ip::tcp::acceptor> acceptor_;
  std::unique_ptr<asio::ip::tcp::socket> client_;
  unsigned short port_ = 0;
};

TEST(TcpClientTransportTest, ReconnectsWhenThePeerGoesAwayAndComesBack) {
  asio::io_context io;
  Server server(io);
  std::string address = "127.0.0.1:" + std::to_string(server.port());
  TcpClientTransport transport(io, address, RetryOptions{0.02, 0.1});
  std::string received;
  std::vector<TransportState> states;
  std::string last_detail;
  transport.open([&](std::string_view bytes) { received += bytes; },
                 [&](TransportState state, const std::string& detail) {
                   states.push_back(state);
                   last_detail = detail;
                 });

  ASSERT_TRUE(run_until(io, [&] { return transport.state() == TransportState::kOpen && server.client(); }));
  asio::write(*server.client(), asio::buffer(std::string("$CAREV,1\r\n")));
  ASSERT_TRUE(run_until(io, [&] { return received == "$CAREV,1\r\n"; }));
  EXPECT_TRUE(transport.write("$CCCFG,SRC,1\r\n"));
  std::string echoed(14, '\0');
  ASSERT_TRUE(run_until(io, [&] { return server.client()->available() >= 14; }));
  asio::read(*server.client(), asio::buffer(echoed));
  EXPECT_EQ(echoed, "$CCCFG,SRC,1\r\n");

  // The peer goes away: the transport reports it, names the address, retries.
  server.go_away();
  ASSERT_TRUE(run_until(io, [&] { return transport.state() == TransportState::kWaiting; }));
  EXPECT_NE(last_detail.find(address), std::string::npos) << last_detail;
  EXPECT_FALSE(transport.write("lost"));  // nothing queued for a dead link
  size_t before = states.size();
  ASSERT_TRUE(run_until(io, [&] { return states.size() >= before + 4; }));  // refused, refused...
  EXPECT_NE(last_detail.find("retrying in"), std::string::npos) << last_detail;

  // It comes back on the same port: the transport reconnects by itself.
  server.listen(server.port());
  ASSERT_TRUE(run_until(io, [&] { return transport.state() == TransportState::kOpen && server.client(); }));
  asio::write(*server.client(), asio::buffer(std::string("again")));
  ASSERT_TRUE(run_until(io, [&] { return received == "$CAREV,1\r\nagain"; }));
  transport.close();
  EXPECT_EQ(transport.state(), TransportState::kClosed);
}

TEST(TcpClientTransportTest, MalformedAddressIsRejectedAtConstruction) {
  asio::io_context io;
  EXPECT_THROW(TcpClientTransport(io, "no-port"), std::invalid_argument);
}

TEST(TcpClientTransportTest, DestroyedWhileConnectingIsSafe) {
  asio::io_context io;
  {
    TcpClientTransport transport(io, "127.0.0.1:1", RetryOptions{0.01, 0.01});
    transport.open([](std::string_view) {}, [](TransportState, const std::string&) {});
  }
  run_until(io, [] { return false; }, std::chrono::milliseconds(100));  // stale handlers run harmlessly
}

}  // namespace
}  // namespace acomms::link
