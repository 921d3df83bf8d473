// The Forwarder's custody receipts (route/custody_receipt.h says what and
// why): on a link whose modem ACKs, the next hop answers "taken" or
// "refused" in software, and the previous hop keeps what it sent until
// "taken". Kept apart from forwarding itself (forwarder.cpp).
//
// The sender's side. on_sent notes every wrapped send (identity, next
// hop). At its link's ACK, keeps_after_ack holds a message whose next hop
// is not its destination (a destination delivers, it never refuses) when
// the link's modem ACKs: it stays in its queue and in the journal, and
// outgoing() holds it back until its wait runs out (receipt_wait_s: 600 s
// after the first offer, doubling to an hour), when it is offered again
// (a retry event). "taken" from that next hop ends it (an acked event);
// "refused" starts that offer's wait again (one doubling per offer, not
// per answer). Its ttl still counts (expiry drops it as any queued
// message, but reports no expiry to its origin: forwarder_receipts.cpp),
// it goes nowhere in any form meanwhile, nothing is sent while it waits (no busy
// loop), and the notes are in memory only: after a restart the journal
// gives the message back as queued, and it is offered again at once.
//
// The receiver's side. take_custody (forwarder.cpp) owes a receipt to the
// node that handed the envelope over; owed_on hands the owed receipts of a
// link to the queues' next frame there.
//
// Core thread only.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/core_thread.h"
#include "route/forwarder.h"
#include "route/forwarder_internal.h"

namespace acomms::route {

using namespace internal;

namespace {

constexpr double kFirstReceiptWaitS = 600;  // an Iridium buoy's next sessions come within this
constexpr double kLongestReceiptWaitS = 3600;
// Notes of sent messages (wrapped_, held_for_receipt_, offers_): past
// this, those of messages no longer queued are dropped (forget_gone); a
// queued message's never is, so the queues' own bounds bound them.
constexpr size_t kMaxSentNotes = 4096;
// Receipts owed to previous hops: past this, the oldest "refused" one is
// dropped (its sender offers again after its wait, no loss); a "taken" one
// never is (without it the sender would offer a message held here again).
constexpr size_t kMaxOwedReceipts = 1024;

}  // namespace

double Forwarder::receipt_wait_s(int offers) {
  const int doublings = std::clamp(offers - 1, 0, 16);
  return std::min(kFirstReceiptWaitS * std::ldexp(1.0, doublings), kLongestReceiptWaitS);
}

void Forwarder::owe_custody_receipt(int link, int32_t to, MessageIdentity about, bool taken) {
  for (OwedReceipt& owed : owed_) {
    if (owed.link == link && owed.to == to && owed.about == about) {
      owed.taken = taken;  // the latest word on it
      return;
    }
  }
  if (owed_.size() >= kMaxOwedReceipts) {
    auto refused = std::find_if(owed_.begin(), owed_.end(), [](const OwedReceipt& o) { return !o.taken; });
    if (refused == owed_.end() && !taken) {
      ++stats_.custody_receipts_dropped;
      spdlog::warn("route: custody receipt refused of message {}/{} to node {} dropped: {} owed already", about.origin,
                   about.seq, to, owed_.size());
      return;
    }
    if (refused != owed_.end()) {
      ++stats_.custody_receipts_dropped;
      spdlog::warn("route: {} custody receipts owed: the oldest refused one dropped", owed_.size());
      owed_.erase(refused);
    }
  }
  owed_.push_back({link, to, about, taken});
}

std::string Forwarder::owed_on(int link, int32_t dest, size_t room, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  std::string bytes;
  const size_t each = sealed_size(kCustodyReceiptBytes, auth());
  for (auto it = owed_.begin(); it != owed_.end();) {
    const bool reaches = dest == queue::kAnyDestination || dest == queue::kBroadcast || dest == it->to;
    if (it->link != link || !reaches || bytes.size() + each > room) {
      ++it;
      continue;
    }
    const CustodyVerdict verdict = it->taken ? CustodyVerdict::kTaken : CustodyVerdict::kRefused;
    std::string receipt = encode_custody_receipt({verdict, it->about}, envelope_id_);
    seal_receipt(receipt, auth(), now);
    bytes += receipt;
    ++stats_.custody_receipts_sent;
    spdlog::debug("route: custody receipt {} of message {}/{} to node {}", to_string(verdict), it->about.origin,
                  it->about.seq, it->to);
    it = owed_.erase(it);
  }
  return bytes;
}

void Forwarder::note_wrapped_send(const queue::QueuedMessage& message, const queue::RoutedForm& form) {
  std::optional<Envelope> e = decode_envelope(form.bytes, envelope_id_, nullptr, nullptr);
  if (!e) return;
  // A new offer: no longer waiting for the last one's receipt.
  held_for_receipt_.erase(message.record.id);
  if (wrapped_.size() >= kMaxSentNotes) forget_gone();
  wrapped_[message.record.id] = {e->identity(), message.record.type, form.next_hop, e->destination, 0};
}

void Forwarder::forget_gone() {
  std::set<int64_t> queued;
  for (const queue::Queue* queue : queues_.queues()) {
    for (const queue::QueuedMessage& m : queue->messages()) queued.insert(m.record.id);
  }
  auto prune = [&queued](auto& notes) {
    for (auto it = notes.begin(); it != notes.end();) {
      it = queued.count(it->first) > 0 ? std::next(it) : notes.erase(it);
    }
  };
  prune(wrapped_);
  prune(held_for_receipt_);
  prune(offers_);
}

void Forwarder::forget_sent(int64_t message_id) {
  wrapped_.erase(message_id);
  held_for_receipt_.erase(message_id);
  offers_.erase(message_id);
}

bool Forwarder::keeps_after_ack(const queue::Queue& /*queue*/, const queue::QueuedMessage& message, int link,
                                double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  auto it = wrapped_.find(message.record.id);
  if (it == wrapped_.end()) return false;
  HeldForReceipt held = it->second;
  wrapped_.erase(it);
  // A software ACK came after the custody commit; a destination never
  // refuses (it delivers): the ACK ends it.
  if (hardware_ack_links_.count(link) == 0 || held.next_hop == held.destination) {
    offers_.erase(message.record.id);
    return false;
  }
  if (held_for_receipt_.size() >= kMaxSentNotes || offers_.size() >= kMaxSentNotes) forget_gone();
  // One offer, one doubling (a refusal of it does not double it again).
  const int offers = ++offers_[message.record.id];
  held.until = now + receipt_wait_s(offers);
  spdlog::debug("route: message {} ({}/{}) ACKed by the modem of link {}: kept until node {}'s custody receipt",
                message.record.id, held.identity.origin, held.identity.seq, link_name(link), held.next_hop);
  held_for_receipt_[message.record.id] = std::move(held);
  return true;
}

bool Forwarder::awaiting_custody_receipt(const queue::Queue& queue, const queue::QueuedMessage& message, double now) {
  auto it = held_for_receipt_.find(message.record.id);
  if (it == held_for_receipt_.end()) return false;
  if (now < it->second.until) return true;
  // Refused, and its back-off is over; or no receipt in time (lost, or
  // the next hop never heard the frame): offered again.
  const int32_t next_hop = it->second.next_hop;
  const bool refused = it->second.refused;
  held_for_receipt_.erase(it);
  ++stats_.custody_reoffered;
  queues_.report_routed(queue.type(), queue::QueueEventKind::kRetry, message.record,
                        refused ? "custody refused by node " + std::to_string(next_hop) + " earlier: offered again"
                                : "no custody receipt from node " + std::to_string(next_hop) + " in time: offered again");
  return false;
}

queue::EnvelopeOutcome Forwarder::on_custody_receipt(std::string_view rest, int32_t src, double now) {
  std::optional<CustodyReceipt> receipt = decode_custody_receipt(rest, envelope_id_);
  if (!receipt) {
    ++stats_.malformed;
    spdlog::warn("route: truncated custody receipt from node {}", src);
    return {};
  }
  // Sealed by `src` when auth is configured (route/receipt_seal.h).
  const SealCheck seal = check_receipt_seal(rest, kCustodyReceiptBytes, auth(), src, now, custody_ttl_s_);
  auto done = [used = seal.used] { return consumed(used); };
  if (!seal.ok) {
    refuse_receipt("custody receipt", src, seal.why);
    return done();
  }
  // Which of this node's messages it is about: held since its modem's ACK,
  // or still awaiting that ACK (the receipt overtook it).
  auto about = [&](std::map<int64_t, HeldForReceipt>& notes) {
    return std::find_if(notes.begin(), notes.end(), [&](const auto& note) {
      return note.second.identity == receipt->about && note.second.next_hop == src;
    });
  };
  auto held = about(held_for_receipt_);
  auto sent = about(wrapped_);
  const bool is_held = held != held_for_receipt_.end();
  if (!is_held && sent == wrapped_.end()) {
    ++stats_.custody_receipts_ignored;
    spdlog::debug("route: custody receipt {} of message {}/{} from node {}: nothing waits for it here",
                  to_string(receipt->verdict), receipt->about.origin, receipt->about.seq, src);
    return done();
  }
  ++stats_.custody_receipts_received;
  const int64_t id = is_held ? held->first : sent->first;
  const HeldForReceipt note = is_held ? held->second : sent->second;
  if (receipt->verdict == CustodyVerdict::kTaken) {
    forget_sent(id);
    if (!queues_.custody_passed(note.type, id, "custody receipt from node " + std::to_string(src))) {
      spdlog::debug("route: custody receipt for message {}, no longer queued", id);
    }
    return done();
  }
  // Refused: offered again after a longer wait. One still awaiting its
  // modem's ACK is held at that ACK anyway.
  if (!is_held) return done();
  const int offers = std::max(offers_[id], 1);  // this offer's wait, counted at its ACK
  held->second.until = now + receipt_wait_s(offers);
  held->second.refused = true;
  queue::JournalMessage record;
  record.id = id;
  record.type = note.type;
  record.src = note.identity.origin;
  record.dest = note.destination;
  queues_.report_routed(note.type, queue::QueueEventKind::kRetry, record,
                        "custody refused by node " + std::to_string(src) + " (full): offered again in " +
                            std::to_string(static_cast<int64_t>(receipt_wait_s(offers))) + " s");
  return done();
}

}  // namespace acomms::route
