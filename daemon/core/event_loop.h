#pragma once
// The core thread. Queues, MAC and drivers live on this one thread and are
// touched only from it, so their logic needs no locks; other threads (gRPC
// handlers, signal handling) hand it work with post() or call().

#include <asio/executor_work_guard.hpp>
#include <asio/io_context.hpp>
#include <asio/post.hpp>

#include <functional>
#include <future>
#include <thread>
#include <type_traits>

namespace acomms::core {

class EventLoop {
 public:
  EventLoop();
  ~EventLoop();  // stops and joins
  EventLoop(const EventLoop&) = delete;
  EventLoop& operator=(const EventLoop&) = delete;

  // Starts the core thread.
  void start();
  // Runs the work already posted, then ends the thread; pending timers are
  // dropped. Idempotent.
  void stop();

  asio::io_context& context() { return context_; }
  bool on_core_thread() const { return std::this_thread::get_id() == thread_.get_id(); }

  // Runs `work` on the core thread later.
  void post(std::function<void()> work) { asio::post(context_, std::move(work)); }

  // Runs `work` on the core thread and waits for its result (or exception).
  // With no core thread running (before start(), after stop()) it runs on
  // the caller's thread: nothing else can touch core state then
  // (core_thread.h), and posting it would wait forever for a thread that
  // does not exist (a daemon whose start fails before the loop starts
  // stops what it built through call()).
  template <typename Work>
  auto call(Work work) -> std::invoke_result_t<Work> {
    using Result = std::invoke_result_t<Work>;
    if (on_core_thread() || !thread_.joinable()) return work();
    std::packaged_task<Result()> task(std::move(work));
    std::future<Result> result = task.get_future();
    asio::post(context_, [&task] { task(); });
    return result.get();
  }

 private:
  asio::io_context context_;
  asio::executor_work_guard<asio::io_context::executor_type> keep_running_;
  std::thread thread_;
};

}  // namespace acomms::core
