#pragma once
// The queues' view of a gateway (route/forwarder.h implements it): the one
// seam through which routing changes what the queues send and receive.
//
// Why an interface here: routing sits above the queues (DESIGN.md: route
// uses queue, never the reverse), yet three queue decisions depend on it:
// how a chosen message goes on the air (as it is, wrapped in an envelope
// for a next hop, or not yet: no route), what a received envelope is
// (delivered here, taken into custody, refused), and which queues hold
// messages in custody (they have no DCCL type). A node without routing
// sets none, and its queues behave, and its frames look, exactly as before.
//
// Threads: every call comes from the core thread (QueueManager's).

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "queue/frame.h"
#include "queue/queue.h"
#include "queue/queue_policy.h"
#include "queue/queued_message.h"
#include "queue/received_message.h"

namespace acomms::queue {

// How the message a queue would send next goes on a transmission now.
struct RoutedForm {
  enum class Kind {
    kPlain,    // as it is (its destination is a neighbour, or it is broadcast)
    kWrapped,  // `bytes` (an envelope) to `next_hop`
    kHold,     // not now: no route, or the route is on another link
  } kind = Kind::kPlain;
  std::string bytes;
  int32_t next_hop = 0;
};

// What became of a received envelope.
struct EnvelopeOutcome {
  // Bytes of the frame it used; 0: malformed (the rest of the frame is lost).
  size_t used = 0;
  // Messages for this node inside it, unwrapped and received (at most one).
  std::vector<ReceivedMessage> delivered;
  // Set when the ACK of the transmission that carried the envelope must wait
  // for a custody commit: the ACK goes only if it is still true once the
  // node's receipts are durable (false at once: custody refused).
  std::shared_ptr<std::atomic<bool>> ack_only_if;
};

class Routing {
 public:
  virtual ~Routing() = default;

  // The DCCL id whose header marks an envelope in a frame.
  virtual uint32_t envelope_id() const = 0;

  // Something was heard from `src` on link `link` (any DATA transmission).
  virtual void heard(int link, int32_t src, double now) = 0;
  // `src` acknowledged a transmission of ours on `link`: both ways work.
  virtual void acked_by(int link, int32_t src, double now) = 0;
  // Whether `link`'s driver acknowledges in the modem, before the daemon
  // sees the transmission (so an ACK cannot wait for custody). Told before
  // each reception on that link.
  virtual void set_acks_in_hardware(int link, bool in_hardware) = 0;

  // The envelope at the start of `rest`, heard from `transmission_src` in
  // a transmission to `transmission_dest` (kAnyDestination: not known) on
  // link `link`.
  virtual EnvelopeOutcome on_envelope(std::string_view rest, int32_t transmission_src, int32_t transmission_dest,
                                      int link, std::optional<std::string_view> link_figures, double now) = 0;

  // How `message`, next in `queue`, goes on the transmission `request`
  // asks for.
  virtual RoutedForm outgoing(const Queue& queue, const QueuedMessage& message, const DataRequest& request,
                              double now) = 0;

  // `message` of `queue` went in a frame as `form`: what the sent event
  // adds ("" for none).
  virtual std::string on_sent(const Queue& queue, const QueuedMessage& message, const RoutedForm& form,
                              double now) = 0;
  // What the acked event of `message` adds ("" for none): a wrapped one's
  // ACK is a hop's, not its destination's.
  virtual std::string acked_detail(const Queue& queue, const QueuedMessage& message) = 0;
  // `message` of `queue` expired here (before the expired event): what
  // that event's detail says instead of "ttl passed" ("" for that).
  virtual std::string expired(const Queue& queue, const QueuedMessage& message, double now) = 0;

  // Custody receipts on a link whose modem ACKs (route/custody_receipt.h).
  // Whether `message` of `queue`, whose frame `link` just acknowledged,
  // stays queued (and journaled), no longer in flight, until the next hop's
  // custody receipt: routing then ends it (QueueManager::custody_passed) or
  // offers it again. Default: no, the ACK ends it.
  virtual bool keeps_after_ack(const Queue& /*queue*/, const QueuedMessage& /*message*/, int /*link*/,
                               double /*now*/) {
    return false;
  }
  // Bytes routing owes on `link` to `dest` (kAnyDestination: whoever the
  // transmission goes to): custody receipts for a previous hop, at most
  // `room` bytes, placed last in the transmission's first frame, room kept
  // for them before the contest. Non-empty counts as sent. Default: none.
  virtual std::string owed_on(int /*link*/, int32_t /*dest*/, size_t /*room*/, double /*now*/) { return ""; }

  // The policy of the custody queue named `type`, or nullopt when `type` is
  // not a custody queue's name (QueueManager makes such queues on demand,
  // also at restore).
  virtual std::optional<QueuePolicy> custody_policy(const std::string& type) const = 0;
};

}  // namespace acomms::queue
