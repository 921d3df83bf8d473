#pragma once
// Small helpers shared by forwarder.cpp and forwarder_receipts.cpp; private
// to route/ (no other layer includes this). Pure functions.

#include <atomic>
#include <memory>
#include <optional>
#include <string>

#include "queue/queue.h"
#include "queue/routing.h"
#include "route/envelope.h"
#include "route/forwarder.h"

namespace acomms::route::internal {

inline constexpr double kClockSkewS = 60;  // a copy on another path may be this much "younger"

inline bool is_custody(const std::string& type) { return type.rfind(kCustodyQueuePrefix, 0) == 0; }

inline std::string custody_queue(uint8_t value_tenths) { return kCustodyQueuePrefix + std::to_string(value_tenths); }

// The envelope a custody message holds (its bytes are ours: always valid).
inline std::optional<Envelope> held_envelope(const queue::QueuedMessage& message, uint32_t envelope_id) {
  return decode_envelope(message.encoded, envelope_id, nullptr, nullptr);
}

inline double remaining_ttl(const queue::Queue& queue, const queue::QueuedMessage& message, double now) {
  return queue.ttl_of(message) - (now - message.record.submitted_at);
}

// An envelope read to its end, with nothing more to say.
inline queue::EnvelopeOutcome consumed(size_t used) {
  queue::EnvelopeOutcome outcome;
  outcome.used = used;
  return outcome;
}

// ... whose transmission's ACK waits on `condition`.
inline queue::EnvelopeOutcome taken_only_if(size_t used, std::shared_ptr<std::atomic<bool>> condition) {
  queue::EnvelopeOutcome outcome = consumed(used);
  outcome.ack_only_if = std::move(condition);
  return outcome;
}

}  // namespace acomms::route::internal
