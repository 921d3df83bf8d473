#pragma once
#include <cstdint>

namespace acomms::queue {

// Counters per queue, from start-up: every way a message leaves or cycles.
struct QueueStats {
  uint64_t queued = 0;
  uint64_t sent = 0;
  uint64_t acked = 0;
  uint64_t expired = 0;
  uint64_t dropped = 0;
  uint64_t retried = 0;
  uint64_t received = 0;
};

}  // namespace acomms::queue
