#pragma once
// A message waiting in a queue: what the journal holds, plus its DCCL
// encoding (ready to stitch into a frame) and whether it is in flight.

#include <cstdint>
#include <string>

#include "queue/message_journal.h"

namespace acomms::queue {

struct QueuedMessage {
  JournalMessage record;
  std::string encoded;          // DCCL bytes, as they go on the wire
  uint64_t in_flight_frame = 0; // frame it was sent in while awaiting an ack; 0 if none
};

}  // namespace acomms::queue
