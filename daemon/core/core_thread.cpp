#include "core/core_thread.h"

#include <spdlog/spdlog.h>

#include <atomic>
#include <cstdlib>

namespace acomms::core {
namespace {

// How many threads hold a mark. Relaxed is enough: a thread that starts a
// loop and then calls into core state from elsewhere has already ordered
// the two by starting the loop (thread creation synchronises).
std::atomic<int> running_core_threads{0};
thread_local bool is_core_thread = false;

}  // namespace

CoreThreadMark::CoreThreadMark() {
  is_core_thread = true;
  running_core_threads.fetch_add(1, std::memory_order_relaxed);
}

CoreThreadMark::~CoreThreadMark() {
  running_core_threads.fetch_sub(1, std::memory_order_relaxed);
  is_core_thread = false;
}

bool may_touch_core_state() {
  return is_core_thread || running_core_threads.load(std::memory_order_relaxed) == 0;
}

void core_thread_violation(const char* function) {
  spdlog::critical("{} must run on the core thread; called from another thread while the core runs",
                   function);
  spdlog::default_logger()->flush();
  std::abort();
}

}  // namespace acomms::core
