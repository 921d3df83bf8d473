// The Forwarder's receipts (route/receipt.h): end-to-end acks and expiry
// reports sent from where a message ended, and what its origin makes of
// them; and the events a routed message's sends and hop ACKs carry. Kept
// apart from forwarding itself (forwarder.cpp). Core thread only, but for
// the journal's completion in journal_into_custody.
#include <spdlog/spdlog.h>

#include "core/core_thread.h"
#include "route/forwarder.h"
#include "route/forwarder_internal.h"

namespace acomms::route {

using namespace internal;

void Forwarder::journal_into_custody(queue::JournalMessage record, MessageIdentity identity,
                                     std::shared_ptr<std::atomic<bool>> taken) {
  // A receipt of ours (no taken flag) has no identity yet: counted apart.
  const bool receipt = taken == nullptr;
  if (receipt) {
    ++pending_receipts_;
  } else {
    pending_[identity] = taken;
  }
  queues_.journal_custody(record, [this, record, identity, taken, receipt](int64_t id, std::exception_ptr error) {
    // The journal's thread: note a failure at once (the ACK's check runs
    // later on the core), and hand the rest to the core.
    if (error && taken) taken->store(false);
    post_([this, record, identity, taken, receipt, id, ok = !error] {
      if (receipt) {
        --pending_receipts_;
      } else {
        pending_.erase(identity);
      }
      // Custody that came on a modem-ACK link: its receipt, now.
      std::optional<std::pair<int, int32_t>> answer;
      if (auto r = receipt_on_commit_.find(identity); !receipt && r != receipt_on_commit_.end()) {
        answer = r->second;
        receipt_on_commit_.erase(r);
      }
      if (!ok) {
        if (answer) owe_custody_receipt(answer->first, answer->second, identity, false);
        if (receipt) {
          spdlog::error("route: {} for node {} not stored: not sent", record.type, record.dest);
        } else {
          spdlog::error("route: custody of message {}/{} not stored: no ACK, the previous hop sends again",
                        identity.origin, identity.seq);
        }
        return;
      }
      queue::QueuedMessage message;
      message.record = record;
      message.record.id = id;
      message.encoded = record.payload;
      const bool accepted = queues_.accept_custody(std::move(message));
      if (!accepted && taken) taken->store(false);
      if (answer) owe_custody_receipt(answer->first, answer->second, identity, accepted);
    });
  });
}

void Forwarder::originate_receipt(int32_t to, Receipt receipt, uint8_t value_tenths, double now) {
  if (held() >= max_custody_) {
    spdlog::warn("route: {} receipt of message {}/{} not sent: custody full (routing.max_custody)",
                 to_string(receipt.kind), to, receipt.seq);
    return;
  }
  Envelope e;
  e.origin = static_cast<uint16_t>(own_id_);
  e.destination = static_cast<uint16_t>(to);
  e.seq = 0;  // its journal id's, when it first goes (outgoing)
  e.hops = 1;
  e.hop_limit = static_cast<uint8_t>(hop_limit_);
  e.ttl_s = ttl_to_seconds(custody_ttl_s_);
  e.value_tenths = value_tenths;  // as urgent as the message it is about
  e.payload = encode_receipt(receipt, envelope_id_);
  seal_receipt(e.payload, auth(), now);  // as this node, when auth is configured
  queue::JournalMessage record;
  record.type = custody_queue(value_tenths);
  record.payload = encode_envelope(e, envelope_id_);
  record.src = own_id_;
  record.dest = to;
  record.submitted_at = now;
  record.ttl_s = custody_ttl_s_;
  ++stats_.receipts_sent;
  spdlog::debug("route: {} receipt of message {}/{} to node {}", to_string(receipt.kind), to, receipt.seq, to);
  journal_into_custody(std::move(record), {}, nullptr);
}

void Forwarder::refuse_receipt(const char* what, int32_t from, const std::string& why) {
  ++stats_.receipts_refused;
  spdlog::warn("route: {} from node {} refused: {} (with auth configured every receipt must be sealed by the node "
               "that reports)",
               what, from, why);
}

void Forwarder::report_expired(const Envelope& e, double now) {
  if (e.origin == own_id_ || starts_envelope(e.payload, envelope_id_)) return;  // ours, or a receipt: no report
  if (!table_.next_hop(e.origin, now)) {
    spdlog::info("route: message {}/{} expired here; no route back to node {}: not reported", e.origin, e.seq,
                 e.origin);
    return;
  }
  originate_receipt(e.origin, {ReceiptKind::kExpired, e.seq}, e.value_tenths, now);
}

void Forwarder::on_receipt(const Envelope& e, const Receipt& receipt) {
  ++stats_.receipts_received;
  const bool delivered = receipt.kind == ReceiptKind::kDelivered;
  // Only the destination can say it delivered: a delivered receipt from any
  // other node (a stale one after the sequence wrapped, or a forged one) is
  // refused and the note stays for the real one. An expiry report may come
  // from any node on the way.
  if (const RoutedSend* noted = awaiting_.find(receipt.seq); noted != nullptr && delivered && e.origin != noted->dest) {
    spdlog::warn("route: end-to-end ack of message {} from node {}, not its destination {}: ignored",
                 noted->message_id, e.origin, noted->dest);
    return;
  }
  std::optional<RoutedSend> send = awaiting_.take(receipt.seq);
  if (!send) {
    // Sent before a restart of a node with no RouteJournal, long ago
    // (past the note's forget_after or the bound), or twice.
    spdlog::info("route: {} receipt from node {} for message seq {}, which this node no longer knows",
                 to_string(receipt.kind), e.origin, receipt.seq);
    return;
  }
  queue::JournalMessage message;
  message.id = send->message_id;
  message.type = send->type;
  message.src = own_id_;
  message.dest = send->dest;
  const std::string detail = delivered ? "delivered to node " + std::to_string(e.origin) + " (end-to-end ack)"
                                       : "expired at node " + std::to_string(e.origin);
  queues_.report_routed(send->type, delivered ? queue::QueueEventKind::kDelivered : queue::QueueEventKind::kExpired,
                        message, detail);
}

std::string Forwarder::on_sent(const queue::Queue& queue, const queue::QueuedMessage& message,
                               const queue::RoutedForm& form, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!is_custody(queue.type())) {
    // No receipt can come after the message's ttl, the receipt's own
    // (custody_ttl_s_, originate_receipt) and the clocks' skew.
    const double forget_after = now + remaining_ttl(queue, message, now) + custody_ttl_s_ + kClockSkewS;
    awaiting_.sent({message.record.id, queue.type(), message.record.dest, form.next_hop, now, false, forget_after});
  }
  note_wrapped_send(message, form);
  return "to node " + std::to_string(message.record.dest) + " through node " + std::to_string(form.next_hop);
}

std::string Forwarder::acked_detail(const queue::Queue& queue, const queue::QueuedMessage& message) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (is_custody(queue.type())) return "hop ack: custody passed on";
  if (!awaiting_.hop_acked(message.record.id)) return "";
  const RoutedSend* send = awaiting_.find(static_cast<uint16_t>(message.record.id & 0xffff));
  return "hop ack from node " + std::to_string(send->next_hop) + ": with next hop, awaiting the end-to-end ack of node " +
         std::to_string(send->dest);
}

std::string Forwarder::expired(const queue::Queue& queue, const queue::QueuedMessage& message, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  // Held for its next hop's custody receipt, its modem having ACKed it: the
  // next hop most likely holds it and passes it on (only its receipt was
  // lost). An expiry report would make the origin drop its note (a later
  // end-to-end ack ignored, a resend delivered twice): none goes; the
  // origin hears the end-to-end ack, or an expiry report from downstream.
  auto held = held_for_receipt_.find(message.record.id);
  const bool awaiting = held != held_for_receipt_.end() && !held->second.refused;
  const int32_t next_hop = awaiting ? held->second.next_hop : 0;
  forget_sent(message.record.id);
  if (awaiting) {
    ++stats_.expired_awaiting_receipt;
    const std::string detail = "ttl ran out awaiting node " + std::to_string(next_hop) +
                               "'s custody receipt; node " + std::to_string(next_hop) +
                               "'s modem had acknowledged it (not reported as expired to its origin)";
    spdlog::warn("route: message {} ({}): {}", message.record.id, queue.type(), detail);
    return detail;
  }
  if (!is_custody(queue.type())) return "";
  if (std::optional<Envelope> e = held_envelope(message, envelope_id_)) report_expired(*e, now);
  return "";
}

}  // namespace acomms::route
