#pragma once
// A message taken off the link: what the queue's receive side hands on to
// subscribers and telemetry, and what its filter (receive_filter.h) judges.
// A plain value, safe to move between threads.

#include <google/protobuf/message.h>

#include <cstdint>
#include <memory>
#include <string>

namespace acomms::queue {

struct ReceivedMessage {
  std::string type;
  std::unique_ptr<google::protobuf::Message> message;
  std::string encoded;  // its DCCL bytes, as received
  int64_t seq = 0;      // its received sequence number (QueueEvent::seq)
  int32_t src = -1;   // from the source role, else the transmission's source
  int32_t dest = 0;
  double time = 0;    // when it was received
};

}  // namespace acomms::queue
