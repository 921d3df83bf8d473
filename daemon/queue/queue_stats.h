#pragma once
#include <cstdint>

namespace acomms::queue {

// Counters per queue, from start-up: every way a message leaves or cycles.
struct QueueStats {
  uint64_t queued = 0;
  uint64_t sent = 0;
  uint64_t acked = 0;
  uint64_t expired = 0;         // ttl ran out in this node's queue
  uint64_t expired_remote = 0;  // routed: reported expired at another node on the way
  uint64_t dropped = 0;
  uint64_t retried = 0;
  uint64_t received = 0;
  uint64_t delivered = 0;  // end-to-end acks of routed messages (route/receipt.h)
  // Submits a full REFUSE_NEW queue refused before they were stored (they
  // have no id and no events). A Submit already on its way to the disk
  // when the queue filled is stored, then dropped: counted in `dropped`.
  uint64_t refused = 0;
};

}  // namespace acomms::queue
