#include "core/event_loop.h"

#include <spdlog/spdlog.h>

namespace acomms::core {

EventLoop::EventLoop() : keep_running_(asio::make_work_guard(context_)) {}

EventLoop::~EventLoop() { stop(); }

void EventLoop::start() {
  thread_ = std::thread([this] {
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
