#include "core/event_loop.h"

#include <spdlog/spdlog.h>

#include "core/core_thread.h"

namespace acomms::core {

EventLoop::EventLoop() : keep_running_(asio::make_work_guard(context_)) {}

EventLoop::~EventLoop() { stop(); }

void EventLoop::start() {
  // start() returns once the thread is marked: from then on, a call into
  // core state from any other thread fails its assertion (core_thread.h).
  std::promise<void> marked;
  std::future<void> marked_future = marked.get_future();
  thread_ = std::thread([this, &marked] {
    CoreThreadMark mark;
    marked.set_value();
    // A handler that throws is a bug in the core; log it and keep the link
    // running rather than take the daemon down with queued data in memory.
    for (;;) {
      try {
        context_.run();
        return;
      } catch (const std::exception& e) {
        spdlog::error("core: unhandled exception: {}", e.what());
      }
    }
  });
  marked_future.wait();
}

void EventLoop::stop() {
  if (!thread_.joinable()) return;
  keep_running_.reset();
  // Posted work runs in order, so everything posted before this runs first;
  // future timers (slots, expiries) are abandoned.
  asio::post(context_, [this] { context_.stop(); });
  thread_.join();
}

}  // namespace acomms::core
