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

  // `when_stored` is this router's own chain (queue/durable_receipts.h).
  ReceivedMessageRouter(ToTelemetry telemetry, queue::WhenStored when_stored, Publish publish);

  // `from` is the transmission that carried the message (its link figures
  // go to subscribers with it).
  void route(const queue::ReceivedMessage& message, const v1::ModemTransmission& from);

 private:
  ToTelemetry telemetry_;
  queue::WhenStored when_stored_;
  Publish publish_;
};

}  // namespace acomms::node
