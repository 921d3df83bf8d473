#include "link/udp_transport.h"

#include <asio/ip/udp.hpp>
#include <asio/steady_timer.hpp>
#include <spdlog/spdlog.h>

#include "link/address.h"
#include "link/backoff.h"
#include "link/driver.h"

namespace acomms::link {

namespace {
std::string to_string(const asio::ip::udp::endpoint& endpoint) {
  const auto address = endpoint.address();
  std::string host = address.is_v6() ? "[" + address.to_string() + "]" : address.to_string();
  return host + ":" + std::to_string(endpoint.port());
}
}  // namespace

struct UdpTransport::Impl : std::enable_shared_from_this<Impl> {
  Impl(asio::io_context& context, RetryOptions retry)
      : context(context), socket(context), timer(context), backoff(retry.min_s, retry.max_s) {}

  asio::io_context& context;
  asio::ip::udp::socket socket;
  asio::steady_timer timer;
  Backoff backoff;
  std::string listen_address;
  HostPort listen;
  std::vector<std::string> peer_addresses;
  std::vector<HostPort> peers;
  std::vector<asio::ip::udp::endpoint> peer_endpoints;
  DatagramCallback on_datagram;
  TransportStateCallback on_state;
  TransportState state = TransportState::kClosed;
  uint64_t generation = 0;
  std::vector<char> buffer = std::vector<char>(kMaxDatagram + 1);
  asio::ip::udp::endpoint sender;

  void set_state(TransportState s, const std::string& detail) {
    state = s;
    if (on_state) on_state(s, detail);
  }

  // Binds the socket; "" or why not.
  std::string bind() {
    set_state(TransportState::kOpening, listen_address);
    std::error_code ec;
    asio::ip::udp::resolver resolver(context);
    auto results = resolver.resolve(listen.host, listen.port, asio::ip::udp::resolver::passive, ec);
    if (ec || results.empty()) return "cannot resolve " + listen_address + ": " + ec.message();
    asio::ip::udp::endpoint endpoint = *results.begin();
    socket.open(endpoint.protocol(), ec);
    // No SO_REUSEADDR: on UDP it would let a second daemon bind the same
    // port and silently take half of the traffic.
    if (!ec) socket.bind(endpoint, ec);
    if (ec) {
      std::error_code ignored;
      socket.close(ignored);
      return "cannot bind " + listen_address + ": " + ec.message();
    }
    backoff.reset();
    set_state(TransportState::kOpen, listen_address);
    receive();
    return "";
  }

  void receive() {
    auto self = shared_from_this();
    uint64_t gen = generation;
    socket.async_receive_from(asio::buffer(buffer), sender, [self, gen](const std::error_code& ec, size_t n) {
      if (gen != self->generation) return;
      if (ec == asio::error::connection_refused || ec == asio::error::message_size) {
        // An ICMP "port unreachable" for an earlier send (a peer not
        // running), or an oversized datagram: not the socket's fault.
        return self->receive();
      }
      if (ec) return self->fail("receive failed: " + ec.message());
      if (self->on_datagram) self->on_datagram(std::string_view(self->buffer.data(), n), to_string(self->sender));
      if (gen == self->generation) self->receive();
    });
  }

  void fail(const std::string& why) {
    ++generation;
    std::error_code ignored;
    socket.close(ignored);
    auto delay = backoff.next();
    std::string detail = listen_address + ": " + why + "; rebinding in " + format_seconds(delay);
    spdlog::warn("udp {}", detail);
    set_state(TransportState::kWaiting, detail);
    auto self = shared_from_this();
    uint64_t gen = generation;
    timer.expires_after(delay);
    timer.async_wait([self, gen](const std::error_code& ec) {
      if (ec || gen != self->generation) return;
      std::string error = self->bind();
      if (!error.empty()) self->fail(error);
    });
  }

  void close() {
    ++generation;
    std::error_code ignored;
    timer.cancel();
    socket.close(ignored);
    state = TransportState::kClosed;  // no callback: the owner asked for it
    on_datagram = nullptr;
    on_state = nullptr;
  }
};

UdpTransport::UdpTransport(asio::io_context& context, const std::string& listen,
                           const std::vector<std::string>& peers, RetryOptions retry)
    : impl_(std::make_shared<Impl>(context, retry)) {
  impl_->listen_address = listen;
  impl_->listen = parse_host_port(listen, "udp listen address", /*allow_port_zero=*/true);
  for (const auto& peer : peers) {
    impl_->peer_addresses.push_back(peer);
    impl_->peers.push_back(parse_host_port(peer, "udp peer address"));
  }
}

UdpTransport::~UdpTransport() { close(); }

void UdpTransport::open(DatagramCallback on_datagram, TransportStateCallback on_state) {
  impl_->close();
  impl_->peer_endpoints.clear();
  asio::ip::udp::resolver resolver(impl_->context);
  for (size_t i = 0; i < impl_->peers.size(); ++i) {
    std::error_code ec;
    auto results = resolver.resolve(impl_->peers[i].host, impl_->peers[i].port, ec);
    if (ec || results.empty()) {
      throw DriverError("udp peer " + impl_->peer_addresses[i] + ": cannot resolve: " + ec.message());
    }
    impl_->peer_endpoints.push_back(*results.begin());
  }
  impl_->on_datagram = std::move(on_datagram);
  impl_->on_state = std::move(on_state);
  impl_->backoff.reset();
  std::string error = impl_->bind();
  if (!error.empty()) {
    impl_->close();
    throw DriverError("udp " + error);
  }
}

void UdpTransport::close() { impl_->close(); }

std::string UdpTransport::send_to_peers(std::string_view datagram) {
  if (impl_->state != TransportState::kOpen) return "udp " + impl_->listen_address + " is not open";
  std::string errors;
  for (size_t i = 0; i < impl_->peer_endpoints.size(); ++i) {
    std::error_code ec;
    // Synchronous: a datagram send does not block on a healthy socket, and
    // the driver wants to know at once whether it went out.
    impl_->socket.send_to(asio::buffer(datagram.data(), datagram.size()), impl_->peer_endpoints[i], 0, ec);
    if (ec && ec != asio::error::connection_refused) {
      errors += (errors.empty() ? "" : "; ") + impl_->peer_addresses[i] + ": " + ec.message();
    }
  }
  return errors;
}

TransportState UdpTransport::state() const { return impl_->state; }

uint16_t UdpTransport::local_port() const {
  if (impl_->state != TransportState::kOpen) return 0;
  std::error_code ec;
  auto endpoint = impl_->socket.local_endpoint(ec);
  return ec ? 0 : endpoint.port();
}

}  // namespace acomms::link
