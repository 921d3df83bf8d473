#pragma once
// Forwarding with custody: what makes a node a gateway (config `routing`,
// README "Gateways: routes and the envelope").
//
// The problem. A shore commands a vehicle that only a buoy hears. The buoy
// must pass the command on without loading the command's type, must not
// lose it when it crashes between hearing and sending, must not let the
// shore forget it before the buoy holds it, and must not send it around a
// loop forever; the vehicle must act on it once even when it came twice.
//
// The decision (the envelope's layout: route/envelope.h):
//  - Origin. A unicast message whose route's next hop is not its
//    destination goes wrapped in an envelope (origin this node, sequence
//    its journal id mod 2^16, hops 1, the type's value_base, its remaining
//    ttl), to the next hop, on the route's link only. A destination that is
//    a neighbour gets the plain DCCL message (no cost). A unicast message
//    with no route at all waits in its queue (its ttl still counts).
//  - Gateway. An envelope addressed to this node (the transmission's
//    destination) for another node is taken into custody: journaled with
//    hops + 1 in a custody queue (one per priority level, named
//    acomms.route.Custody.v<value_base x 10>), and the transmission's ACK
//    goes only once that is committed (queue/routing.h). Full custody
//    (routing.max_custody) refuses it: no ACK, the previous hop keeps it.
//    A copy already held is acknowledged, not stored twice. An envelope
//    whose hops reached its limit, or whose ttl ran out, is dropped with a
//    warning and acknowledged (the loop ends here). Custody messages go on
//    as they came, with their remaining ttl restamped, to the route's next
//    hop on its link; they wait while there is no route. A held message
//    never blocks a sendable one behind it (queue/frame_building.cpp).
//    A link whose modem ACKs in hardware (Micro-Modem, Iridium: Driver::
//    acks_in_hardware) cannot withhold its ACK: the previous hop forgets
//    the message as the modem answers. There, full custody takes it over
//    routing.max_custody (a soft bound, warned and counted) rather than
//    lose it; only links with software ACKs (sim, udp, Micro-Modem FDP)
//    leave a refused message with the previous hop.
//  - Destination. An envelope for this node is unwrapped and received like
//    any frame, from its origin, once per identity (origin, sequence): a
//    second copy within its ttl is counted and dropped, after a restart
//    too (the identity is journaled with the received event; delivered_
//    identities.h). Then an end-to-end ack (route/receipt.h) goes back to
//    the origin, routed and with custody like any message.
//  - Expiry. A message whose ttl runs out in custody here (or that arrives
//    with none left) is reported to its origin, if a route back exists now.
//  - Origin. A receipt for this node is logged as an event of the message
//    it is about: "delivered" (end-to-end ack), or "expired" with where;
//    its hop ACK was "acked" ("hop ack from node 2").
//  - Routes are learned: any frame from a node on a link (it is a
//    neighbour there), an ACK from it, and an envelope's origin through the
//    node that handed it over (route/route_table.h).
// An envelope inside an envelope's payload is never acted on.

// Threads: core thread only (queue::Routing's calls), but for the journal's
// completion of a custody append, which posts to the core (PostToCore).

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "core/clock.h"
#include "dccl/codec.h"
#include "queue/queue_manager.h"
#include "queue/routing.h"
#include "route/delivered_identities.h"
#include "route/end_to_end_ack.h"
#include "route/envelope.h"
#include "route/receipt.h"
#include "route/route_journal.h"
#include "route/route_table.h"

namespace acomms::route {

// Name prefix of custody queues ("acomms.route.Custody.v10": value_base 1).
inline constexpr const char* kCustodyQueuePrefix = "acomms.route.Custody.v";

struct ForwarderStats {
  uint64_t custody_taken = 0;      // envelopes for another node handed to the journal
                                   // (a failed commit is logged, not acknowledged)
  uint64_t custody_refused = 0;    // ... refused: custody full (no ACK)
  uint64_t custody_copies = 0;     // ... already held: acknowledged, not stored again
  uint64_t delivered = 0;          // envelopes for this node delivered to its subscribers
  uint64_t duplicates = 0;         // ... a copy of one already delivered: dropped
  uint64_t hop_limit_dropped = 0;  // envelopes dropped at their hop limit
  uint64_t expired_dropped = 0;    // envelopes that arrived with no ttl left
  uint64_t malformed = 0;          // bytes that start like an envelope but are not one
  uint64_t overheard = 0;          // envelopes for others addressed to another next hop
  uint64_t custody_over_bound = 0; // taken past max_custody: the modem had ACKed them
  uint64_t receipts_sent = 0;      // end-to-end acks and expiry reports originated here
  uint64_t receipts_received = 0;  // ... that reached this node, as the origin
};

class Forwarder final : public queue::Routing {
 public:
  using PostToCore = std::function<void(std::function<void()>)>;

  // `links`: the node's link names by index (DataRequest::link). `custody_ttl_s`:
  // the ttl a custody queue's priority grows over (the queues' default
  // ttl_s). Throws std::invalid_argument naming the routing field (routes,
  // hop_limit, envelope_id, max_custody) or the type whose DCCL id is the
  // envelope's, and reserves that id in `codec` (a type loaded later with
  // it is refused). `queues` and `codec` must outlive the forwarder; call
  // queues.set_routing(this) before queues.restore(). `journal` (may be
  // null: memory only) keeps the end-to-end notes and learned routes
  // across a restart (route_journal.h); it is read here and must outlive
  // the forwarder.
  Forwarder(const v1::RoutingConfig& config, int32_t own_id, std::vector<std::string> links,
            dccl::Codec& codec, queue::QueueManager& queues, const core::Clock& clock, double custody_ttl_s,
            PostToCore post, RouteJournal* journal = nullptr);

  const RouteTable& routes() const { return table_; }
  RouteTable& routes() { return table_; }
  // Why `message`, queued in `queue`, cannot go now ("no route to node
  // 5"), or "" when it may (queue ls). Core thread.
  std::string waiting(const queue::Queue& queue, const queue::QueuedMessage& message) const;
  // A custody message's envelope head as JSON ({"origin":1,...}), or ""
  // for a message of a DCCL type (queue ls).
  std::string custody_json(const queue::Queue& queue, const queue::QueuedMessage& message) const;
  // Every route now (RouteTable::list at the clock's now).
  std::vector<RouteEntry> list_routes() const { return table_.list(clock_.now_seconds()); }
  // Where a message for `dest` goes next now, or nullopt: no route (queue ls).
  std::optional<NextHop> next_hop(int32_t dest) const { return table_.next_hop(dest, clock_.now_seconds()); }
  const ForwarderStats& stats() const { return stats_; }
  // Messages held for others now: in custody queues or being journaled.
  size_t held() const;
  // This node's messages sent wrapped and not yet heard of end to end.
  const EndToEndAcks& awaiting_end_to_end() const { return awaiting_; }
  // Whether a routed message (origin, seq) was delivered here and is
  // remembered still.
  bool delivered(const MessageIdentity& identity) { return delivered_.contains(identity, clock_.now_seconds()); }

  // queue::Routing
  uint32_t envelope_id() const override { return envelope_id_; }
  void heard(int link, int32_t src, double now) override;
  void acked_by(int link, int32_t src, double now) override;
  void set_acks_in_hardware(int link, bool in_hardware) override;
  queue::EnvelopeOutcome on_envelope(std::string_view rest, int32_t transmission_src, int32_t transmission_dest,
                                     int link, std::optional<std::string_view> link_figures, double now) override;
  queue::RoutedForm outgoing(const queue::Queue& queue, const queue::QueuedMessage& message,
                             const queue::DataRequest& request, double now) override;
  std::optional<queue::QueuePolicy> custody_policy(const std::string& type) const override;
  std::string on_sent(const queue::Queue& queue, const queue::QueuedMessage& message, const queue::RoutedForm& form,
                      double now) override;
  std::string acked_detail(const queue::Queue& queue, const queue::QueuedMessage& message) override;
  void expired(const queue::Queue& queue, const queue::QueuedMessage& message, double now) override;

 private:
  // forwarder_receipts.cpp: a receipt about (origin, seq) from here to
  // `to`, journaled into custody; one that came here.
  void originate_receipt(int32_t to, Receipt receipt, uint8_t value_tenths, double now);
  void on_receipt(const Envelope& e, const Receipt& receipt);
  void report_expired(const Envelope& e, double now);
  // Journals `record` (an envelope) into its custody queue; `taken` false
  // when the commit fails.
  void journal_into_custody(queue::JournalMessage record, MessageIdentity identity,
                            std::shared_ptr<std::atomic<bool>> taken);
  queue::EnvelopeOutcome deliver_here(const Envelope& e, size_t used, int link,
                                      std::optional<std::string_view> link_figures, double now);
  queue::EnvelopeOutcome take_custody(Envelope e, size_t used, int link, double now);
  bool holds(const MessageIdentity& identity) const;
  const std::string& link_name(int link) const;
  std::string receipt_json(const std::string& payload) const;

  RouteTable table_;
  int32_t own_id_;
  std::vector<std::string> links_;
  queue::QueueManager& queues_;
  const core::Clock& clock_;
  double custody_ttl_s_;
  PostToCore post_;
  uint32_t envelope_id_;
  uint32_t hop_limit_;
  uint32_t max_custody_;
  bool unwrapping_ = false;         // receiving an envelope's payload now
  bool refusing_ = false;           // custody refused since the last taken (logged once)
  // Custody being journaled: identity -> whether it is (still) taken. A
  // copy arriving meanwhile is ACKed on the same condition.
  std::map<MessageIdentity, std::shared_ptr<std::atomic<bool>>> pending_;
  DeliveredIdentities delivered_;
  EndToEndAcks awaiting_;
  size_t pending_receipts_ = 0;  // receipts being journaled
  std::set<int> hardware_ack_links_;
  ForwarderStats stats_;
};

}  // namespace acomms::route
