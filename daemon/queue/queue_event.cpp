#include "queue/queue_event.h"

#include "queue/message_journal.h"

namespace acomms::queue {

// These words are stored in event_log.kind and shown to operators: changing
// one breaks every query and tool that reads the log.
std::string_view to_string(QueueEventKind kind) {
  switch (kind) {
    case QueueEventKind::kQueued:
      return "queued";
    case QueueEventKind::kSent:
      return "sent";
    case QueueEventKind::kAcked:
      return "acked";
    case QueueEventKind::kExpired:
      return "expired";
    case QueueEventKind::kDropped:
      return "dropped";
    case QueueEventKind::kRetry:
      return "retry";
    case QueueEventKind::kReceived:
      return "received";
    case QueueEventKind::kPacket:
      return "packet";
    case QueueEventKind::kDelivered:
      return "delivered";
  }
  return "unknown";
}

QueueEvent queued_event(const JournalMessage& message) {
  QueueEvent event;
  event.kind = QueueEventKind::kQueued;
  event.time = message.submitted_at;
  event.type = message.type;
  event.message_id = message.id;
  event.src = message.src;
  event.dest = message.dest;
  return event;
}

}  // namespace acomms::queue
