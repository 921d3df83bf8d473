#pragma once
// What happens to queued messages. Every change of a message's fate is an
// event: counted, logged, and written to the store's event log, so that a
// message never disappears silently.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace acomms::queue {

enum class QueueEventKind {
  kQueued,    // accepted by Submit (durable)
  kSent,      // placed in a frame handed to the driver
  kAcked,     // its frame was acknowledged: done
  kExpired,   // ttl passed before it was delivered: dropped
  kDropped,   // pushed out by a full queue, or refused by one
  kRetry,     // sent, not acknowledged: eligible again
  kReceived,  // arrived from the link and was passed on
  // Not a message's fate: one packet heard from another node, decoded or
  // not, with its link figures (measured and predicted SNR; LinkFigures.
  // decoded). type "" and message_id 0. What acommsctl link calibrate fits.
  kPacket,
  // A routed message's end-to-end ack came back from its destination
  // (route/receipt.h): it arrived there. Its hop's ACK was kAcked.
  kDelivered,
};

std::string_view to_string(QueueEventKind kind);

// A message that came wrapped in a routing envelope (route/envelope.h):
// which it was, and until when a copy of it must be known as one.
struct RoutedIdentity {
  int32_t origin = 0;
  int32_t seq = 0;
  double forget_after = 0;  // Clock seconds
};

struct QueueEvent {
  QueueEventKind kind = QueueEventKind::kQueued;
  double time = 0;        // Clock seconds since the Unix epoch
  std::string type;       // DCCL message type
  int64_t message_id = 0; // 0 for received messages
  uint64_t frame_id = 0;  // kSent, kAcked, kRetry: the frame; 0 otherwise
  int32_t src = -1;       // modem ids, -1 when unknown
  int32_t dest = -1;
  std::string detail;     // human-readable reason (e.g. "queue full: oldest dropped")
  // True when this event ends the message's life in the queue (acked,
  // expired, dropped, or sent in a frame that asked for no ack): the store
  // forgets the message in the same transaction that logs the event.
  bool removes_message = false;
  std::string encoded;  // kReceived: the message's DCCL bytes (see DuplicateFilter)
  // kReceived: its received sequence number (1, 2, ...; never reused, see
  // migrations/0005_received_sequence.sql); 0 on every other kind.
  int64_t seq = 0;
  // kReceived: the link figures of the transmission that carried it, a
  // serialized acomms.v1.LinkFigures (link/link_figures.h) the queue only
  // carries, never reads. nullopt: none came with it (every other kind, and
  // received events logged before migrations/0008_link_figures.sql); an
  // empty string is a LinkFigures whose fields are all default, not none.
  std::optional<std::string> link_figures;
  // kReceived of an authenticated type (dccl/message_auth.h): its send
  // time as stamped, Unix seconds. The store keeps (type, encoded) in
  // auth_accepted with it (migrations/0009_auth_accepted.sql), in the same
  // transaction as the event, so a replay is recognised after a restart,
  // and forgets there what was stamped before auth_forget_before.
  std::optional<uint32_t> auth_sent_s;
  double auth_forget_before = 0;
  // With auth_sent_s: the source of the transmission that carried it (the
  // sender its tag was verified for, migrations/0011). nullopt in rows
  // accepted before senders were told apart: their bytes are refused from
  // any sender.
  std::optional<int32_t> auth_sender;
  // kReceived of a message unwrapped from an envelope: its identity, kept
  // with the event (migrations/0013_route_delivered.sql) so that a copy
  // arriving after a restart is still delivered once.
  std::optional<RoutedIdentity> routed;
};

struct JournalMessage;
// The event that records `message` entering its queue (written by the
// journal with the message itself).
QueueEvent queued_event(const JournalMessage& message);

}  // namespace acomms::queue
