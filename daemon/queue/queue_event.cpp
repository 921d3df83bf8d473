#include "queue/queue_event.h"

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
  }
  return "unknown";
}

}  // namespace acomms::queue
