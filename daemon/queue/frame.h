#pragma once
// What the link asks the queues for, and what they give back.

#include <cstdint>
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
