#pragma once
// "Core thread only", checked. Queues, MAC, link controller and drivers are
// lock-free because one thread owns them (event_loop.h); a call from any
// other thread is a data race that tests rarely catch and the field finds.
// So the functions documented "core thread only" say so in code:
//
//   void QueueManager::on_ack(uint64_t frame_id) {
//     ACOMMS_ASSERT_CORE_THREAD();
//
// The rule it checks: while a core thread runs (an EventLoop has started and
// not stopped), only that thread may call. While none runs (start-up before
// the loop, shutdown after it, unit tests that drive a node on the simulated
// scheduler from the test's own thread) the caller owns everything and any
// thread passes. The check is a thread-local read and a relaxed atomic load,
// so it stays on in every build, Release included: a violation logs the
// function and aborts.

namespace acomms::core {

// Marks the calling thread as a core thread for the mark's lifetime. The
// EventLoop's thread holds one while it runs; nothing else should need to.
class CoreThreadMark {
 public:
  CoreThreadMark();
  ~CoreThreadMark();
  CoreThreadMark(const CoreThreadMark&) = delete;
  CoreThreadMark& operator=(const CoreThreadMark&) = delete;
};

// True on a marked core thread, or on any thread while no core thread runs.
bool may_touch_core_state();

// Logs "`function` must run on the core thread" and aborts.
[[noreturn]] void core_thread_violation(const char* function);

}  // namespace acomms::core

#define ACOMMS_ASSERT_CORE_THREAD()                                              \
  do {                                                                           \
    if (!::acomms::core::may_touch_core_state()) {                               \
      ::acomms::core::core_thread_violation(__PRETTY_FUNCTION__);                \
    }                                                                            \
  } while (0)
