#pragma once
// Where a message the link received goes: telemetry's types to the
// telemetry node, every other type to the subscribers.
//
// The problem: telemetry's messages are bits of a stream, not news for a
// subscriber (what they carry comes out as Position, once reconstructed);
// and any other message may be published only once its event (and so its
// seq) is committed: a subscriber must never hold a number that a crash
// could hand out again, and a replay must find every message published
// before it (service/subscribe_rpc.cpp relies on this).
//
// The decision: each destination is a function given at construction, so
// this rule is the whole of the class and is tested without a store, a
// link or a telemetry node. A message whose event may not be stored is
// still published (logged): it was heard, and the sender will not send it
// again once its ACK went out.
//
// Telemetry's messages are handed on later (`later`: after the core's
// current work), not at once: telemetry numbers the Positions it
// reconstructs from the received sequence, and the messages that came in
// the same transmission already hold lower numbers, so their "publish once
// stored" requests must reach the store writer before the Positions' write
// does. Otherwise a Position would be published before them and a live
// subscriber, which skips what is not newer than what it last sent, would
// lose them (service/subscribe_rpc.cpp).
//
// Not thread-safe: route() runs on the core thread (the LinkController's
// receive callback). `publish` runs on the store writer's thread: commits
// complete in order, so messages are published in seq order.

#include <functional>

#include "acomms/v1/acomms.pb.h"
#include "acomms/v1/modem_transmission.pb.h"
#include "queue/durable_receipts.h"
#include "queue/queue_manager.h"

namespace acomms::node {

class ReceivedMessageRouter {
 public:
  using ToTelemetry = std::function<void(const queue::ReceivedMessage& message)>;
  using Publish = std::function<void(const v1::ReceivedMessage& message)>;
  // Runs the work on the core thread after what it is doing now.
  using Later = std::function<void(std::function<void()> work)>;

  // `when_stored` is this router's own chain (queue/durable_receipts.h).
  ReceivedMessageRouter(ToTelemetry telemetry, queue::WhenStored when_stored, Publish publish, Later later);

  // `from` is the transmission that carried the message (its link figures
  // go to subscribers with it).
  void route(queue::ReceivedMessage message, const v1::ModemTransmission& from);

 private:
  ToTelemetry telemetry_;
  queue::WhenStored when_stored_;
  Publish publish_;
  Later later_;
};

}  // namespace acomms::node
