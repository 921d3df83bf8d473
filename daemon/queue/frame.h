#pragma once
// What the link asks the queues for, and what they give back.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace acomms::queue {

inline constexpr int32_t kAnyDestination = -1;

// A transmission opportunity (a MAC slot), as the driver describes it.
struct DataRequest {
  // Who the transmission is for; kAnyDestination lets the first message
  // chosen decide (every later message must then be for the same node or
  // broadcast).
  int32_t dest = kAnyDestination;
  uint32_t max_frame_bytes = 0;
  uint32_t max_num_frames = 1;
  // Whether this transmission can carry an acknowledgement back.
  bool ack_requested = true;
  // Which of the node's links asks (its index; 0 when there is one). What
  // a link's earlier transmission left awaiting an ACK comes back into the
  // contest at that link's next request, not another's: a message is on
  // one link at a time, and an ACK that comes late on its link still finds
  // it (QueueManager::release_in_flight frees a link's messages early).
  int link = 0;
  // Whether this link may carry a message of `type` to `dest` now, the
  // type's priority being `priority` (its P when this request came, before
  // it won any place): the node's choice of link (link/link_choice.h).
  // `dest` is the next hop of a message that goes wrapped in an envelope.
  // Unset: every message.
  std::function<bool(const std::string& type, int32_t dest, double priority)> may_carry;
  // Whether the transmission goes even if the queues give it nothing (a
  // MAC slot: an empty one still sends its broadcast frame). False (a
  // satellite modem's session, held only for what the queues give): nothing
  // of the node's own (queue/piggyback.h) may be what makes it transmit.
  bool in_slot = false;
};

// One modem frame: DCCL messages back to back (they self-delimit, so no
// header is needed).
struct Frame {
  uint64_t frame_id = 0;  // unique; an ack names it
  int32_t dest = 0;
  bool ack_requested = false;
  std::string bytes;
  std::vector<int64_t> message_ids;
};

}  // namespace acomms::queue
