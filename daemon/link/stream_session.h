#pragma once
// What the serial and TCP client transports share: one byte stream that is
// read continuously and written from a queue, and that, when it fails, is
// closed and opened again after an exponential backoff, each state change
// reported.
//
// Handlers hold a shared_ptr to the session, so an operation that completes
// after close() (with operation_aborted) never touches freed memory; the
// generation number tells stale handlers from current ones.
//
// `Derived` (CRTP) opens the stream: open_stream() reports kOpening, then
// ends in opened() or fail(); cancel_opening() stops an open in progress;
// read_failure(ec) words a read error. `kind` ("serial", "tcp") starts its
// log lines and `name` (device, address) names the stream.

#include <asio/io_context.hpp>
#include <asio/steady_timer.hpp>
#include <asio/write.hpp>
#include <spdlog/spdlog.h>

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>

#include "link/backoff.h"
#include "link/transport_state.h"

namespace acomms::link {

template <typename Derived, typename Stream>
struct StreamSession : std::enable_shared_from_this<Derived> {
  using DataCallback = std::function<void(std::string_view bytes)>;

  StreamSession(asio::io_context& context, const char* kind, std::string name, RetryOptions retry)
      : stream(context), timer(context), kind(kind), name(std::move(name)), backoff(retry.min_s, retry.max_s) {}

  Stream stream;
  asio::steady_timer timer;
  const char* kind;
  std::string name;
  Backoff backoff;
  DataCallback on_data;
  TransportStateCallback on_state;
  TransportState state = TransportState::kClosed;
  uint64_t generation = 0;
  std::array<char, 4096> buffer{};
  std::deque<std::string> outbox;
  bool writing = false;

  Derived& derived() { return static_cast<Derived&>(*this); }

  void set_state(TransportState s, const std::string& detail) {
    state = s;
    if (on_state) on_state(s, detail);
  }

  // The transport's open(): starts over with these callbacks.
  void start(DataCallback data, TransportStateCallback state_change) {
    close();
    on_data = std::move(data);
    on_state = std::move(state_change);
    backoff.reset();
    derived().open_stream();
  }

  // The stream is open: report it and start reading.
  void opened() {
    backoff.reset();
    set_state(TransportState::kOpen, name);
    read();
  }

  // The transport's write(): false (dropped) while the stream is not open.
  bool write(std::string_view bytes) {
    if (state != TransportState::kOpen) return false;
    outbox.emplace_back(bytes);
    flush();
    return true;
  }

  void read() {
    auto self = this->shared_from_this();
    uint64_t gen = generation;
    stream.async_read_some(asio::buffer(buffer), [self, gen](const std::error_code& ec, size_t n) {
      if (gen != self->generation) return;
      if (ec) return self->fail(self->derived().read_failure(ec));
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
    auto self = this->shared_from_this();
    uint64_t gen = generation;
    asio::async_write(stream, asio::buffer(*bytes), [self, gen, bytes](const std::error_code& ec, size_t) {
      if (gen != self->generation) return;
      self->writing = false;
      if (ec) return self->fail("write failed: " + ec.message());
      self->flush();
    });
  }

  void fail(const std::string& why) {
    ++generation;  // whatever is still in flight belongs to the old stream
    std::error_code ignored;
    stream.close(ignored);
    outbox.clear();
    writing = false;
    auto delay = backoff.next();
    std::string detail = name + ": " + why + "; retrying in " + format_seconds(delay);
    spdlog::warn("{} {}", kind, detail);
    set_state(TransportState::kWaiting, detail);
    auto self = this->shared_from_this();
    uint64_t gen = generation;
    timer.expires_after(delay);
    timer.async_wait([self, gen](const std::error_code& ec) {
      if (ec || gen != self->generation) return;
      self->derived().open_stream();
    });
  }

  void close() {
    ++generation;
    std::error_code ignored;
    derived().cancel_opening();
    timer.cancel();
    stream.close(ignored);
    outbox.clear();
    writing = false;
    // No state callback: the owner asked for this, and may be mid-destruction.
    state = TransportState::kClosed;
    on_data = nullptr;
    on_state = nullptr;
  }
};

}  // namespace acomms::link
