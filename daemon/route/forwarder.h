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
//    A link whose modem ACKs in hardware (Micro-Modem without FDP,
//    Iridium: Driver::acks_in_hardware) cannot withhold its ACK. There the
//    hop's answer is a custody receipt in software (route/custody_
//    receipt.h, 56 bits): "taken" once the custody commit is done (or the
//    copy is already held), "refused" when custody is full (nothing is
//    stored, routing.max_custody is a hard bound on every link). The
//    previous hop keeps the message, queued and journaled, past its
//    modem's ACK until "taken"; it offers it again after "refused" or
//    when no receipt came in time, with a back-off (forwarder_custody.cpp).
//    Each hop is judged by its own link: a node with a software-ACK
//    acoustic link and an Iridium link withholds ACKs on the one and sends
//    custody receipts on the other. Both ends of one link must agree (the
//    same driver kind, the same FDP setting); a receipt the sender does not
//    wait for is ignored there.
//  - Destination. An envelope for this node is unwrapped and received like
//    any frame, from its origin, once per identity (origin, sequence): a
//    second copy within its ttl is counted and dropped, after a restart
//    too (the identity is journaled with the received event; delivered_
//    identities.h). Then an end-to-end ack (route/receipt.h) goes back to
//    the origin, routed and with custody like any message.
//  - Expiry. A message whose ttl runs out in custody here (or that arrives
//    with none left) is reported to its origin, if a route back exists now;
//    not one held for its next hop's custody receipt after that hop's modem
//    ACKed it (the next hop most likely holds it: only logged, its expired
//    event says so, and the origin waits for the end-to-end ack).
//  - Origin. A receipt for this node is logged as an event of the message
//    it is about: "delivered" (end-to-end ack), or "expired" with where;
//    its hop ACK was "acked" ("hop ack from node 2").
//  - Routes are learned: any frame from a node on a link (it is a
//    neighbour there), an ACK from it, and an envelope's origin through the
//    node that handed it over (route/route_table.h).
// An envelope inside an envelope's payload is never acted on.
// With auth configured, every receipt is sealed and checked (route/
// receipt_seal.h): a forged one changes nothing.

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
#include "route/custody_receipt.h"
#include "route/delivered_identities.h"
#include "route/end_to_end_ack.h"
#include "route/envelope.h"
#include "route/receipt.h"
#include "route/receipt_seal.h"
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
  uint64_t receipts_sent = 0;      // end-to-end acks and expiry reports originated here
  uint64_t receipts_received = 0;  // ... that reached this node, as the origin
  // Custody receipts (route/custody_receipt.h), links whose modem ACKs:
  uint64_t custody_receipts_sent = 0;      // "taken" and "refused" sent to a previous hop
  uint64_t custody_receipts_received = 0;  // ... heard about a message this node held for one
  uint64_t custody_receipts_ignored = 0;   // ... about nothing this node waits for, or from another node
  uint64_t custody_reoffered = 0;          // messages offered again: refused, or no receipt in time
  uint64_t custody_receipts_dropped = 0;   // owed receipts dropped at their bound ("refused" ones only)
  uint64_t expired_awaiting_receipt = 0;   // ttl ran out here while held for a next hop's receipt
  // Receipts (end-to-end or custody) refused: unsealed, forged or stale
  // while auth is configured (route/receipt_seal.h).
  uint64_t receipts_refused = 0;
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
  bool keeps_after_ack(const queue::Queue& queue, const queue::QueuedMessage& message, int link,
                       double now) override;
  std::string owed_on(int link, int32_t dest, size_t room, double now) override;

  // A sent message held for its next hop's custody receipt
  // (forwarder_custody.cpp), by journal id: until when, and from whom.
  struct HeldForReceipt {
    MessageIdentity identity;
    std::string type;
    int32_t next_hop = 0;
    int32_t destination = 0;
    double until = 0;
    bool refused = false;  // the next hop said "refused" to its last offer
  };
  const std::map<int64_t, HeldForReceipt>& held_for_receipt() const { return held_for_receipt_; }
  // The wait for a custody receipt after the `offers`-th offer: 600 s
  // doubling, at most an hour.
  static double receipt_wait_s(int offers);
  std::string on_sent(const queue::Queue& queue, const queue::QueuedMessage& message, const queue::RoutedForm& form,
                      double now) override;
  std::string acked_detail(const queue::Queue& queue, const queue::QueuedMessage& message) override;
  std::string expired(const queue::Queue& queue, const queue::QueuedMessage& message, double now) override;

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
  queue::EnvelopeOutcome take_custody(Envelope e, size_t used, int link, int32_t from, double now);
  // forwarder_custody.cpp: custody receipts.
  void owe_custody_receipt(int link, int32_t to, MessageIdentity about, bool taken);
  queue::EnvelopeOutcome on_custody_receipt(std::string_view rest, int32_t src, double now);
  // Whether `message` waits for a custody receipt now (outgoing: hold); a
  // wait that ran out offers it again.
  bool awaiting_custody_receipt(const queue::Queue& queue, const queue::QueuedMessage& message, double now);
  void note_wrapped_send(const queue::QueuedMessage& message, const queue::RoutedForm& form);
  void forget_sent(int64_t message_id);
  // Drops the notes (wrapped_, held_for_receipt_, offers_) of messages no
  // longer in any queue: called when one of them reaches its bound.
  void forget_gone();
  bool holds(const MessageIdentity& identity) const;
  const std::string& link_name(int link) const;
  // The fleet's authenticator, or null: receipts sealed and checked with it
  // (route/receipt_seal.h).
  const dccl::MessageAuthenticator* auth() const { return codec_.authenticator(); }
  // A receipt from `from` refused by its seal: counted and logged.
  void refuse_receipt(const char* what, int32_t from, const std::string& why);
  std::string receipt_json(const std::string& payload) const;

  RouteTable table_;
  const dccl::Codec& codec_;
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
  // Custody receipts (forwarder_custody.cpp). Owed to previous hops, sent
  // in this node's next frame on their link:
  struct OwedReceipt {
    int link = 0;
    int32_t to = 0;
    MessageIdentity about;
    bool taken = false;
  };
  std::vector<OwedReceipt> owed_;
  // Custody being journaled that came on a modem-ACK link: its receipt
  // goes once the commit is done (link, previous hop).
  std::map<MessageIdentity, std::pair<int, int32_t>> receipt_on_commit_;
  // Wrapped sends awaiting their link's ACK, by journal id. Bounded by the
  // queues' own bounds: a note is dropped only once its message left every
  // queue (forget_gone), never while it may still be ACKed.
  std::map<int64_t, HeldForReceipt> wrapped_;
  std::map<int64_t, HeldForReceipt> held_for_receipt_;
  std::map<int64_t, int> offers_;  // offers so far of a held message (back-off)
};

}  // namespace acomms::route
