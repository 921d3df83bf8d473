#include "iridium_shore/mo_server.h"

#include <spdlog/spdlog.h>

#include <asio/ip/tcp.hpp>
#include <asio/read.hpp>
#include <asio/steady_timer.hpp>
#include <asio/write.hpp>

#include <set>

#include "iridium_shore/direct_ip.h"
#include "link/driver.h"

namespace acomms::drivers {

using asio::ip::tcp;

namespace {

struct Connection {
  explicit Connection(asio::io_context& context) : socket(context), timer(context) {}
  tcp::socket socket;
  asio::steady_timer timer;
  std::string peer;
  std::string buffer;
  bool closed = false;
};

}  // namespace

struct MoServer::Impl : std::enable_shared_from_this<Impl> {
  Impl(asio::io_context& c, HostAndPort a, std::string l, uint32_t m, std::chrono::milliseconds t)
      : context(c), address(std::move(a)), listen(std::move(l)), max_connections(m), read_timeout(t), acceptor(c) {}

  asio::io_context& context;
  HostAndPort address;
  std::string listen;
  uint32_t max_connections;
  std::chrono::milliseconds read_timeout;
  tcp::acceptor acceptor;
  bool open = false;
  bool accepting = false;
  // Counts open() calls: an accept from before a close() must not count
  // as the accept of the reopened server.
  uint64_t generation = 0;
  std::set<std::shared_ptr<Connection>> connections;
  OnMessage on_message;
  OnBadInput on_bad_input;

  void accept_next() {
    if (!open || accepting || connections.size() >= max_connections) return;
    accepting = true;
    auto connection = std::make_shared<Connection>(context);
    acceptor.async_accept(connection->socket, [self = shared_from_this(), connection,
                                               generation = generation](std::error_code error) {
      if (!self->open || generation != self->generation) return;
      self->accepting = false;
      if (error) {
        spdlog::warn("iridium shore: accepting an MO connection on {} failed: {}", self->listen, error.message());
        // Out of descriptors, say: try again in a while, not in a tight loop.
        auto pause = std::make_shared<asio::steady_timer>(self->context, std::chrono::milliseconds(100));
        pause->async_wait([self, pause, generation](std::error_code) {
          if (self->open && generation == self->generation) self->accept_next();
        });
        return;
      } else {
        std::error_code ignored;
        auto remote = connection->socket.remote_endpoint(ignored);
        connection->peer = ignored ? "?" : remote.address().to_string() + ":" + std::to_string(remote.port());
        self->connections.insert(connection);
        self->read(connection);
      }
      self->accept_next();
    });
  }

  void drop(const std::shared_ptr<Connection>& connection) {
    if (connection->closed) return;
    connection->closed = true;
    std::error_code ignored;
    connection->timer.cancel();
    connection->socket.shutdown(tcp::socket::shutdown_both, ignored);
    connection->socket.close(ignored);
    connections.erase(connection);
    accept_next();  // a place is free again
  }

  void bad(const std::shared_ptr<Connection>& connection, const std::string& kind, const std::string& detail) {
    if (on_bad_input) on_bad_input(kind, detail + " (from " + connection->peer + ")");
    drop(connection);
  }

  // Runs `then` after `limit`, unless the connection is gone or the timer
  // is set again first.
  void arm(const std::shared_ptr<Connection>& connection, std::chrono::milliseconds limit,
           std::function<void()> then) {
    connection->timer.expires_after(limit);
    connection->timer.async_wait([connection, then = std::move(then)](std::error_code error) {
      if (!error && !connection->closed) then();
    });
  }

  void read(const std::shared_ptr<Connection>& connection) {
    std::weak_ptr<Impl> weak = weak_from_this();
    arm(connection, read_timeout, [weak, connection] {
      if (auto self = weak.lock()) {
        self->bad(connection, "MO read timeout",
                  "an MO connection sent " + std::to_string(connection->buffer.size()) +
                      " bytes and then nothing for the read limit");
      }
    });
    connection->buffer.resize(directip::kPrefixBytes);
    asio::async_read(connection->socket, asio::buffer(connection->buffer),
                     [self = shared_from_this(), connection](std::error_code error, size_t) {
                       if (connection->closed || !self->open) return;
                       if (error) return self->bad(connection, "MO connection cut off", "closed before its prefix");
                       std::string why;
                       std::optional<uint16_t> length = directip::parse_prefix(connection->buffer, &why);
                       if (!length) return self->bad(connection, "MO refused", why);
                       self->read_body(connection, *length);
                     });
  }

  void read_body(const std::shared_ptr<Connection>& connection, size_t length) {
    connection->buffer.resize(directip::kPrefixBytes + length);
    asio::async_read(
        connection->socket, asio::buffer(connection->buffer.data() + directip::kPrefixBytes, length),
        [self = shared_from_this(), connection, length](std::error_code error, size_t got) {
          if (connection->closed || !self->open) return;
          if (error) {
            return self->bad(connection, "MO connection cut off",
                             "closed after " + std::to_string(got) + " of " + std::to_string(length) + " bytes");
          }
          self->hold(connection);
        });
  }

  // The message is read: the owner answers it when it is durable.
  void hold(const std::shared_ptr<Connection>& connection) {
    std::weak_ptr<Impl> weak = weak_from_this();
    arm(connection, std::chrono::duration_cast<std::chrono::milliseconds>(kHoldLimit), [weak, connection] {
      if (auto self = weak.lock()) {
        spdlog::error("iridium shore: an MO from {} was not made durable within {} s: closed unanswered",
                      connection->peer, kHoldLimit.count());
        self->drop(connection);
      }
    });
    auto finish = [weak, connection](std::string reply) {
      auto self = weak.lock();
      if (!self || connection->closed) return;
      if (reply.empty()) return self->drop(connection);
      auto bytes = std::make_shared<std::string>(std::move(reply));
      asio::async_write(connection->socket, asio::buffer(*bytes), [weak, connection, bytes](std::error_code, size_t) {
        if (auto self = weak.lock()) self->drop(connection);
      });
    };
    if (on_message) on_message(std::move(connection->buffer), finish);
  }
};

MoServer::MoServer(asio::io_context& context, HostAndPort listen, std::string label, uint32_t max_connections,
                   std::chrono::milliseconds read_timeout)
    : impl_(std::make_shared<Impl>(context, std::move(listen), std::move(label), max_connections, read_timeout)) {}

MoServer::~MoServer() { close(); }

void MoServer::open(OnMessage on_message, OnBadInput on_bad_input) {
  close();
  const HostAndPort& address = impl_->address;
  try {
    tcp::resolver resolver(impl_->context);
    auto endpoints = resolver.resolve(address.host, address.port, tcp::resolver::passive);
    tcp::endpoint endpoint = endpoints.begin()->endpoint();
    impl_->acceptor.open(endpoint.protocol());
    impl_->acceptor.set_option(tcp::acceptor::reuse_address(true));
    impl_->acceptor.bind(endpoint);
    impl_->acceptor.listen();
  } catch (const std::system_error& e) {
    std::error_code ignored;
    impl_->acceptor.close(ignored);
    throw link::DriverError("iridium shore: cannot listen for MOs on " + impl_->listen + ": " + e.what());
  }
  impl_->on_message = std::move(on_message);
  impl_->on_bad_input = std::move(on_bad_input);
  impl_->open = true;
  ++impl_->generation;
  impl_->accept_next();
}

void MoServer::close() {
  if (!impl_->open) return;
  impl_->open = false;
  std::error_code ignored;
  impl_->acceptor.close(ignored);
  impl_->accepting = false;
  for (auto connection : std::set<std::shared_ptr<Connection>>(impl_->connections)) impl_->drop(connection);
  impl_->on_message = nullptr;
  impl_->on_bad_input = nullptr;
}

uint16_t MoServer::local_port() const {
  std::error_code error;
  auto endpoint = impl_->acceptor.local_endpoint(error);
  return error ? 0 : endpoint.port();
}

size_t MoServer::connections() const { return impl_->connections.size(); }

}  // namespace acomms::drivers
