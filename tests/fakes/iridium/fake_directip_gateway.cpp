#include "fake_directip_gateway.h"

#include <asio/connect.hpp>
#include <asio/executor_work_guard.hpp>
#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/post.hpp>
#include <asio/read.hpp>
#include <asio/steady_timer.hpp>
#include <asio/write.hpp>

#include <deque>
#include <map>
#include <mutex>
#include <thread>

namespace acomms::fake_iridium {

using asio::ip::tcp;

namespace {

void u8(std::string& out, unsigned value) { out.push_back(static_cast<char>(value & 0xff)); }
void u16(std::string& out, unsigned value) {
  u8(out, value >> 8);
  u8(out, value);
}
void u32(std::string& out, uint32_t value) {
  u16(out, value >> 16);
  u16(out, value & 0xffff);
}
unsigned get16(const std::string& s, size_t at) {
  return (static_cast<uint8_t>(s[at]) << 8) | static_cast<uint8_t>(s[at + 1]);
}

// The MT confirmation, IEI 0x44 (spec §9.3.4): 31 bytes.
std::string mt_confirmation(uint32_t client_id, const std::string& imei, uint32_t auto_id, int16_t status) {
  std::string out;
  u8(out, 1);
  u16(out, 28);
  u8(out, 0x44);
  u16(out, 25);
  u32(out, client_id);
  out += (imei + std::string(15, '0')).substr(0, 15);
  u32(out, status < 0 ? 0 : auto_id);
  u16(out, static_cast<uint16_t>(status));
  return out;
}

struct PendingMo {
  std::string bytes;
  bool retry = true;  // false: a raw push, tried once
};

}  // namespace

struct FakeDirectIpGateway::Impl : std::enable_shared_from_this<Impl> {
  explicit Impl(Options o) : options(std::move(o)), acceptor(io, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)) {}

  Options options;
  asio::io_context io;
  asio::executor_work_guard<asio::io_context::executor_type> work = asio::make_work_guard(io);
  tcp::acceptor acceptor;
  std::thread thread;

  mutable std::mutex mutex;  // guards everything below
  std::deque<PendingMo> mo;
  bool pushing = false;
  bool shore_reachable = true;
  size_t delivered = 0, attempts = 0, hanging_closed = 0;
  uint32_t next_cdr = 1000;
  std::map<std::string, std::deque<MtMessage>> mt;
  std::vector<MtSubmission> submissions;
  std::optional<int16_t> refuse_next;
  bool hang_next = false;
  bool garble_next = false;
  uint16_t next_mtmsn = 0;
  uint32_t next_auto_id = 500000;
  std::vector<std::shared_ptr<tcp::socket>> held;  // hanging MT connections

  // --- MO: one push at a time, FIFO, retried ---
  void push_next() {
    std::lock_guard lock(mutex);
    if (pushing || mo.empty()) return;
    pushing = true;
    ++attempts;
    if (!shore_reachable) return retry_later_locked();
    auto socket = std::make_shared<tcp::socket>(io);
    auto timer = std::make_shared<asio::steady_timer>(io);
    auto bytes = std::make_shared<std::string>(mo.front().bytes);
    auto self = shared_from_this();
    timer->expires_after(options.mo_answer_timeout);
    timer->async_wait([socket](std::error_code error) {
      std::error_code ignored;
      if (!error) socket->close(ignored);  // the handlers below then see an error
    });
    std::string host = options.shore_mo_address.substr(0, options.shore_mo_address.rfind(':'));
    unsigned short port = static_cast<unsigned short>(std::stoi(options.shore_mo_address.substr(host.size() + 1)));
    socket->async_connect(tcp::endpoint(asio::ip::make_address(host), port), [self, socket, timer, bytes](std::error_code error) {
      if (error) return self->push_done(false, timer);
      asio::async_write(*socket, asio::buffer(*bytes), [self, socket, timer](std::error_code error, size_t) {
        if (error) return self->push_done(false, timer);
        // Confirmation (7 bytes) or the shore's close.
        auto reply = std::make_shared<std::string>(7, '\0');
        asio::async_read(*socket, asio::buffer(*reply), [self, socket, timer, reply](std::error_code error, size_t got) {
          bool ok;
          if (self->options.expect_mo_confirmation) {
            ok = !error && *reply == std::string("\x01\x00\x04\x05\x00\x01\x01", 7);
          } else {
            ok = error == asio::error::eof && got == 0;  // closed, nothing said
          }
          self->push_done(ok, timer);
        });
      });
    });
  }

  void push_done(bool ok, const std::shared_ptr<asio::steady_timer>& timer) {
    timer->cancel();
    std::lock_guard lock(mutex);
    if (ok || !mo.front().retry) {
      if (ok && mo.front().retry) ++delivered;
      mo.pop_front();
      pushing = false;
      asio::post(io, [self = shared_from_this()] { self->push_next(); });
      return;
    }
    retry_later_locked();
  }

  void retry_later_locked() {
    auto timer = std::make_shared<asio::steady_timer>(io, options.mo_retry);
    timer->async_wait([self = shared_from_this(), timer](std::error_code) {
      {
        std::lock_guard lock(self->mutex);
        self->pushing = false;
      }
      self->push_next();
    });
  }

  // --- MT: one message per connection ---
  void accept_mt() {
    auto socket = std::make_shared<tcp::socket>(io);
    acceptor.async_accept(*socket, [self = shared_from_this(), socket](std::error_code error) {
      if (error) return;  // closed
      self->read_mt(socket);
      self->accept_mt();
    });
  }

  void read_mt(const std::shared_ptr<tcp::socket>& socket) {
    auto buffer = std::make_shared<std::string>(3, '\0');
    asio::async_read(*socket, asio::buffer(*buffer), [self = shared_from_this(), socket, buffer](std::error_code error, size_t) {
      if (error || (*buffer)[0] != 1) return;
      size_t length = get16(*buffer, 1);
      if (length > 2048) return;
      buffer->resize(3 + length);
      asio::async_read(*socket, asio::buffer(buffer->data() + 3, length), [self, socket, buffer](std::error_code error, size_t) {
        if (error) return;
        std::string reply = self->answer_mt(*buffer, socket);
        if (reply.empty()) return;  // held
        auto bytes = std::make_shared<std::string>(std::move(reply));
        asio::async_write(*socket, asio::buffer(*bytes), [socket, bytes](std::error_code, size_t) {
          std::error_code ignored;
          socket->shutdown(tcp::socket::shutdown_both, ignored);
          socket->close(ignored);
        });
      });
    });
  }

  // The confirmation for one whole MT message (spec §9.3).
  std::string answer_mt(const std::string& message, const std::shared_ptr<tcp::socket>& socket) {
    std::lock_guard lock(mutex);
    MtSubmission s;
    bool have_header = false, have_payload = false, lengths_ok = true;
    for (size_t at = 3; at < message.size();) {
      if (message.size() - at < 3) { lengths_ok = false; break; }
      unsigned iei = static_cast<uint8_t>(message[at]);
      size_t length = get16(message, at + 1);
      if (length > message.size() - at - 3) { lengths_ok = false; break; }
      std::string content = message.substr(at + 3, length);
      if (iei == 0x41) {
        if (length != 21) { lengths_ok = false; break; }
        s.client_id = (get16(content, 0) << 16) | get16(content, 2);
        s.imei = content.substr(4, 15);
        s.flags = static_cast<uint16_t>(get16(content, 19));
        have_header = true;
      } else if (iei == 0x42) {
        s.payload = content;
        have_payload = true;
      }
      at += 3 + length;
    }
    bool imei_ok = s.imei.size() == 15 && s.imei.find_first_not_of("0123456789") == std::string::npos;
    if (hang_next) {
      hang_next = false;
      s.answered = false;
      submissions.push_back(s);
      held.push_back(socket);
      return "";
    }
    if (garble_next) {
      garble_next = false;
      s.answered = false;
      submissions.push_back(s);
      return std::string("\x01\x00\x05\x44\x00\x02\x00\x00", 8);
    }
    auto& queue = mt[s.imei];
    if (refuse_next) {
      s.status = *refuse_next;
      refuse_next.reset();
    } else if (!lengths_ok || !have_header) {
      s.status = -7;
    } else if (!imei_ok) {
      s.status = -1;
    } else if (!have_payload || s.payload.empty()) {
      s.status = -4;
    } else if (s.payload.size() > 270) {
      s.status = -3;
    } else if (queue.size() >= 50) {
      s.status = -5;
    } else if ((s.flags & 0x20) && (s.client_id < 1 || s.client_id > 65535)) {
      s.status = -11;
    } else {
      uint16_t mtmsn;
      if (s.flags & 0x20) {
        mtmsn = static_cast<uint16_t>(s.client_id);
      } else {
        next_mtmsn = next_mtmsn == 65535 ? 1 : next_mtmsn + 1;
        mtmsn = next_mtmsn;
      }
      if (s.flags & 0x01) queue.clear();  // flush MT queue
      queue.push_back({mtmsn, s.payload});
      s.status = static_cast<int16_t>(queue.size());
    }
    submissions.push_back(s);
    return mt_confirmation(s.client_id, s.imei, next_auto_id++, s.status);
  }
};

FakeDirectIpGateway::FakeDirectIpGateway(Options options) : impl_(std::make_shared<Impl>(std::move(options))) {
  impl_->accept_mt();
  impl_->thread = std::thread([impl = impl_] { impl->io.run(); });
}

FakeDirectIpGateway::~FakeDirectIpGateway() {
  impl_->io.stop();
  impl_->thread.join();
}

std::string FakeDirectIpGateway::mo_message(const std::string& imei, uint16_t momsn, const std::string& payload,
                                            uint32_t cdr, uint32_t time) {
  std::string body;
  u8(body, 0x01);  // MO header (spec §9.2.1)
  u16(body, 28);
  u32(body, cdr);
  body += imei;
  u8(body, 0);  // session status: completed
  u16(body, momsn);
  u16(body, 0);  // MTMSN: none
  u32(body, time);
  if (!payload.empty()) {
    u8(body, 0x02);  // MO payload (spec §9.2.2)
    u16(body, static_cast<unsigned>(payload.size()));
    body += payload;
  }
  std::string out;
  u8(out, 1);
  u16(out, static_cast<unsigned>(body.size()));
  return out + body;
}

void FakeDirectIpGateway::mo_received(const std::string& imei, uint16_t momsn, const std::string& payload) {
  if (payload.empty()) return;  // a mailbox check: nothing to push (sbd_gateway.h)
  {
    std::lock_guard lock(impl_->mutex);
    impl_->mo.push_back({mo_message(imei, momsn, payload, impl_->next_cdr++), true});
  }
  asio::post(impl_->io, [impl = impl_] { impl->push_next(); });
}

std::optional<MtMessage> FakeDirectIpGateway::take_mt(const std::string& imei) {
  std::lock_guard lock(impl_->mutex);
  auto& queue = impl_->mt[imei];
  if (queue.empty()) return std::nullopt;
  MtMessage m = std::move(queue.front());
  queue.pop_front();
  return m;
}

int FakeDirectIpGateway::mt_queued(const std::string& imei) const {
  std::lock_guard lock(impl_->mutex);
  auto it = impl_->mt.find(imei);
  return it == impl_->mt.end() ? 0 : static_cast<int>(it->second.size());
}

uint16_t FakeDirectIpGateway::mt_port() const { return impl_->acceptor.local_endpoint().port(); }

size_t FakeDirectIpGateway::mo_pending() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->mo.size();
}
size_t FakeDirectIpGateway::mo_delivered() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->delivered;
}
size_t FakeDirectIpGateway::mo_attempts() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->attempts;
}
std::vector<FakeDirectIpGateway::MtSubmission> FakeDirectIpGateway::mt_submissions() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->submissions;
}
size_t FakeDirectIpGateway::hanging_closed_by_shore() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->hanging_closed;
}

void FakeDirectIpGateway::set_shore_reachable(bool reachable) {
  std::lock_guard lock(impl_->mutex);
  impl_->shore_reachable = reachable;
}

void FakeDirectIpGateway::push_raw_mo(std::string bytes) {
  {
    std::lock_guard lock(impl_->mutex);
    impl_->mo.push_back({std::move(bytes), false});
  }
  asio::post(impl_->io, [impl = impl_] { impl->push_next(); });
}

void FakeDirectIpGateway::open_hanging_mo(std::string bytes) {
  asio::post(impl_->io, [impl = impl_, bytes = std::make_shared<std::string>(std::move(bytes))] {
    auto socket = std::make_shared<tcp::socket>(impl->io);
    std::string host = impl->options.shore_mo_address.substr(0, impl->options.shore_mo_address.rfind(':'));
    auto port = static_cast<unsigned short>(std::stoi(impl->options.shore_mo_address.substr(host.size() + 1)));
    socket->async_connect(tcp::endpoint(asio::ip::make_address(host), port), [impl, socket, bytes](std::error_code error) {
      if (error) return;
      asio::async_write(*socket, asio::buffer(*bytes), [impl, socket, bytes](std::error_code error, size_t) {
        if (error) return;
        auto sink = std::make_shared<char>();
        // Nothing more is sent; the read ends when the shore closes.
        asio::async_read(*socket, asio::buffer(sink.get(), 1), [impl, socket, sink](std::error_code error, size_t) {
          if (!error) return;
          std::lock_guard lock(impl->mutex);
          ++impl->hanging_closed;
        });
      });
    });
  });
}

void FakeDirectIpGateway::refuse_next_mt(int16_t status) {
  std::lock_guard lock(impl_->mutex);
  impl_->refuse_next = status;
}

void FakeDirectIpGateway::garble_next_mt_confirmation() {
  std::lock_guard lock(impl_->mutex);
  impl_->garble_next = true;
}

void FakeDirectIpGateway::hang_next_mt() {
  std::lock_guard lock(impl_->mutex);
  impl_->hang_next = true;
}

}  // namespace acomms::fake_iridium
