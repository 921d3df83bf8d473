#include "iridium_shore/mt_client.h"

#include <asio/connect.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/read.hpp>
#include <asio/steady_timer.hpp>
#include <asio/write.hpp>


namespace acomms::drivers {

using asio::ip::tcp;

namespace {

// One submission: its socket, its one timer, and where it stands.
struct Submission {
  Submission(asio::io_context& context) : resolver(context), socket(context), timer(context) {}
  tcp::resolver resolver;
  tcp::socket socket;
  asio::steady_timer timer;
  std::string message;
  std::string reply;
  std::function<void(MtSubmitResult)> done;
  bool finished = false;
};

}  // namespace

struct MtClient::Impl : std::enable_shared_from_this<Impl> {
  Impl(asio::io_context& c, HostAndPort a, std::string g, std::chrono::milliseconds ct, std::chrono::milliseconds rt)
      : context(c), address(std::move(a)), gateway(std::move(g)), connect_timeout(ct), confirmation_timeout(rt) {}
  asio::io_context& context;
  HostAndPort address;
  std::string gateway;
  std::chrono::milliseconds connect_timeout, confirmation_timeout;
  uint64_t generation = 0;  // close() abandons every submission of an earlier generation

  // Ends `s` once: closes its socket and reports (unless abandoned).
  void finish(const std::shared_ptr<Submission>& s, uint64_t of_generation, MtSubmitResult result) {
    if (s->finished) return;
    s->finished = true;
    std::error_code ignored;
    s->timer.cancel();
    s->resolver.cancel();
    s->socket.close(ignored);
    if (of_generation == generation) s->done(std::move(result));
  }

  void fail(const std::shared_ptr<Submission>& s, uint64_t g, std::string error, bool malformed = false) {
    MtSubmitResult result;
    result.error = std::move(error);
    result.malformed = malformed;
    finish(s, g, std::move(result));
  }

  void arm(const std::shared_ptr<Submission>& s, uint64_t g, std::chrono::milliseconds limit, std::string what) {
    s->timer.expires_after(limit);
    s->timer.async_wait([self = shared_from_this(), s, g, what = std::move(what)](std::error_code error) {
      if (!error) self->fail(s, g, what + " timed out");
    });
  }

  void start(const std::shared_ptr<Submission>& s) {
    const uint64_t g = generation;
    arm(s, g, connect_timeout, "connecting to the MT gateway " + gateway);
    s->resolver.async_resolve(
        address.host, address.port, [self = shared_from_this(), s, g](std::error_code error, tcp::resolver::results_type found) {
          if (s->finished) return;
          if (error) return self->fail(s, g, "resolving the MT gateway " + self->gateway + ": " + error.message());
          asio::async_connect(s->socket, found, [self, s, g](std::error_code error, const tcp::endpoint&) {
            if (s->finished) return;
            if (error) return self->fail(s, g, "connecting to the MT gateway " + self->gateway + ": " + error.message());
            self->send(s, g);
          });
        });
  }

  void send(const std::shared_ptr<Submission>& s, uint64_t g) {
    arm(s, g, confirmation_timeout, "waiting for the MT confirmation from " + gateway);
    asio::async_write(s->socket, asio::buffer(s->message), [self = shared_from_this(), s, g](std::error_code error, size_t) {
      if (s->finished) return;
      if (error) return self->fail(s, g, "sending the MT to " + self->gateway + ": " + error.message());
      s->reply.resize(directip::kPrefixBytes);
      asio::async_read(s->socket, asio::buffer(s->reply), [self, s, g](std::error_code error, size_t) {
        if (s->finished) return;
        if (error) return self->fail(s, g, "the MT gateway closed before its confirmation: " + error.message());
        std::string why;
        std::optional<uint16_t> length = directip::parse_prefix(s->reply, &why);
        if (!length) return self->fail(s, g, "the MT confirmation is malformed: " + why, true);
        s->reply.resize(directip::kPrefixBytes + *length);
        asio::async_read(s->socket, asio::buffer(s->reply.data() + directip::kPrefixBytes, *length),
                         [self, s, g](std::error_code error, size_t) {
                           if (s->finished) return;
                           if (error) return self->fail(s, g, "the MT confirmation was cut off: " + error.message());
                           std::string why;
                           MtSubmitResult result;
                           result.confirmation = directip::parse_mt_confirmation(s->reply, &why);
                           if (!result.confirmation) {
                             return self->fail(s, g, "the MT confirmation is malformed: " + why, true);
                           }
                           self->finish(s, g, std::move(result));
                         });
      });
    });
  }
};

MtClient::MtClient(asio::io_context& context, HostAndPort gateway, std::string label,
                   std::chrono::milliseconds connect_timeout, std::chrono::milliseconds confirmation_timeout)
    : impl_(std::make_shared<Impl>(context, std::move(gateway), std::move(label), connect_timeout,
                                   confirmation_timeout)) {}

MtClient::~MtClient() { close(); }

void MtClient::submit(std::string message, std::function<void(MtSubmitResult)> done) {
  auto s = std::make_shared<Submission>(impl_->context);
  s->message = std::move(message);
  s->done = std::move(done);
  impl_->start(s);
}

void MtClient::close() { ++impl_->generation; }

}  // namespace acomms::drivers
