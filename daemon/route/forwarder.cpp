// Forwarding with custody (forwarder.h says what and why).
#include "route/forwarder.h"

#include <spdlog/spdlog.h>

#include <charconv>
#include <stdexcept>

#include "core/core_thread.h"
#include "route/forwarder_internal.h"

namespace acomms::route {

using namespace internal;

namespace {

queue::RoutedForm hold() {
  queue::RoutedForm form;
  form.kind = queue::RoutedForm::Kind::kHold;
  return form;
}

}  // namespace

Forwarder::Forwarder(const v1::RoutingConfig& config, int32_t own_id, std::vector<std::string> links,
                     dccl::Codec& codec, queue::QueueManager& queues, const core::Clock& clock,
                     double custody_ttl_s, PostToCore post, RouteJournal* journal)
    : table_(config, links, own_id),
      codec_(codec),
      own_id_(own_id),
      links_(std::move(links)),
      queues_(queues),
      clock_(clock),
      custody_ttl_s_(custody_ttl_s),
      post_(std::move(post)),
      envelope_id_(config.has_envelope_id() ? config.envelope_id() : kDefaultEnvelopeId),
      hop_limit_(config.has_hop_limit() ? config.hop_limit() : kDefaultHopLimit),
      max_custody_(config.has_max_custody() ? config.max_custody() : 1000) {
  if (own_id < 1 || own_id > 65535) {
    throw std::invalid_argument("routing: this node's id " + std::to_string(own_id) +
                                " does not fit the envelope (1..65535)");
  }
  if (envelope_id_ < 128 || envelope_id_ > 32767) {
    throw std::invalid_argument("routing.envelope_id " + std::to_string(envelope_id_) + " is not in 128..32767");
  }
  if (const dccl::TypeInfo* taken = codec.find_id(static_cast<int>(envelope_id_))) {
    throw std::invalid_argument("routing.envelope_id " + std::to_string(envelope_id_) + " is the DCCL id of " +
                                taken->name + ": choose another envelope_id");
  }
  // And none loaded later (LoadDefinitions) may take it either.
  codec.reserve_id(static_cast<int>(envelope_id_), "routing.envelope_id (the routing envelope)");
  if (hop_limit_ < 1 || hop_limit_ > kMaxHopLimit) {
    throw std::invalid_argument("routing.hop_limit " + std::to_string(hop_limit_) + " is not in 1..15");
  }
  if (max_custody_ == 0) throw std::invalid_argument("routing.max_custody must be at least 1");
  // What this node delivered before a restart (a SIGKILL included).
  for (const queue::RoutedIdentity& r : queues_.routed_delivered()) {
    delivered_.remember({static_cast<uint16_t>(r.origin), static_cast<uint16_t>(r.seq)}, r.forget_after);
  }
  // And what it sent awaiting end-to-end acks, and the routes it learned.
  awaiting_.attach(journal, clock_.now_seconds());
  table_.attach(journal, clock_.now_seconds());
}

const std::string& Forwarder::link_name(int link) const {
  static const std::string none;
  return link >= 0 && static_cast<size_t>(link) < links_.size() ? links_[static_cast<size_t>(link)] : none;
}

size_t Forwarder::held() const {
  size_t n = pending_.size() + pending_receipts_;
  for (const queue::Queue* queue : queues_.queues()) {
    if (is_custody(queue->type())) n += queue->size();
  }
  return n;
}

bool Forwarder::holds(const MessageIdentity& identity) const {
  for (const queue::Queue* queue : queues_.queues()) {
    if (!is_custody(queue->type())) continue;
    for (const queue::QueuedMessage& m : queue->messages()) {
      if (auto e = held_envelope(m, envelope_id_); e && e->identity() == identity) return true;
    }
  }
  return false;
}

void Forwarder::heard(int link, int32_t src, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  // An envelope's payload comes "from" its origin, which was not heard.
  if (unwrapping_) return;
  table_.heard(src, link_name(link), now);
}

void Forwarder::acked_by(int link, int32_t src, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  table_.heard(src, link_name(link), now, /*two_way=*/true);
}

void Forwarder::set_acks_in_hardware(int link, bool in_hardware) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (in_hardware) {
    hardware_ack_links_.insert(link);
  } else {
    hardware_ack_links_.erase(link);
  }
}

queue::EnvelopeOutcome Forwarder::on_envelope(std::string_view rest, int32_t transmission_src,
                                              int32_t transmission_dest, int link,
                                              std::optional<std::string_view> link_figures, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (unwrapping_) {
    // Inside a delivered envelope's payload: whoever wrapped it there is
    // not the node that handed it over; nothing in it is acted on.
    ++stats_.malformed;
    spdlog::warn("route: an envelope inside an envelope's payload (from node {}): not acted on", transmission_src);
    return {};
  }
  // A next hop's custody receipt (route/custody_receipt.h): not an envelope.
  if (starts_custody_receipt(rest, envelope_id_)) return on_custody_receipt(rest, transmission_src, now);
  size_t used = 0;
  std::string error;
  std::optional<Envelope> e = decode_envelope(rest, envelope_id_, &used, &error);
  if (!e) {
    ++stats_.malformed;
    spdlog::warn("route: bad envelope from node {}: {}", transmission_src, error);
    return {};
  }
  const bool to_us = transmission_dest == queue::kAnyDestination || transmission_dest == own_id_;
  // Handed to us: its origin is reachable back through whoever handed it.
  if (to_us) table_.heard_through(e->origin, transmission_src, link_name(link), now);
  if (e->destination == own_id_) return deliver_here(*e, used, link, link_figures, now);
  if (!to_us) {
    // Overheard on its way to another next hop: not ours to take.
    ++stats_.overheard;
    return consumed(used);
  }
  return take_custody(std::move(*e), used, link, transmission_src, now);
}

queue::EnvelopeOutcome Forwarder::deliver_here(const Envelope& e, size_t used, int link,
                                               std::optional<std::string_view> link_figures, double now) {
  if (delivered_.contains(e.identity(), now)) {
    ++stats_.duplicates;
    spdlog::debug("route: message {}/{} from node {} arrived again: dropped", e.origin, e.seq, e.origin);
    return consumed(used);
  }
  const double forget_after = now + e.ttl_s + kClockSkewS;
  if (starts_envelope(e.payload, envelope_id_)) {
    // Routing's own payload: a receipt for this node (sealed by its origin
    // when auth is configured), or nothing valid.
    const SealCheck seal = check_receipt_seal(e.payload, kReceiptBytes, auth(), e.origin, now, custody_ttl_s_);
    if (!seal.ok) {
      refuse_receipt("end-to-end receipt", e.origin, seal.why);
      return consumed(used);
    }
    std::optional<Receipt> receipt;
    if (seal.used == e.payload.size()) receipt = decode_receipt(e.payload.substr(0, kReceiptBytes), envelope_id_);
    if (!receipt) {
      ++stats_.malformed;
      spdlog::warn("route: envelope {}/{} holds another envelope: dropped", e.origin, e.seq);
      return consumed(used);
    }
    delivered_.remember(e.identity(), forget_after);
    on_receipt(e, *receipt);
    return consumed(used);
  }
  delivered_.remember(e.identity(), forget_after);
  queue::EnvelopeOutcome outcome = consumed(used);
  unwrapping_ = true;
  try {
    outcome.delivered = queues_.receive_routed(e.payload, e.origin, e.seq, forget_after, link_figures, link);
  } catch (...) {
    unwrapping_ = false;
    throw;
  }
  unwrapping_ = false;
  // The end-to-end ack, back to the origin by whatever route leads there,
  // only for a message handed to this node's subscribers: one whose type
  // is not loaded here, whose tag failed, that names another destination or
  // that the receive filter dropped was not delivered, and the origin must
  // not be told it was (it keeps its hop ack only).
  if (outcome.delivered.empty()) {
    spdlog::warn("route: message {}/{} from node {} reached this node but was not delivered: no end-to-end ack",
                 e.origin, e.seq, e.origin);
    return outcome;
  }
  ++stats_.delivered;
  if (e.origin != own_id_) originate_receipt(e.origin, {ReceiptKind::kDelivered, e.seq}, e.value_tenths, now);
  return outcome;
}

queue::EnvelopeOutcome Forwarder::take_custody(Envelope e, size_t used, int link, int32_t from, double now) {
  // This link's modem ACKed already: the answer that counts is a custody
  // receipt (route/custody_receipt.h) to `from`, the previous hop.
  const bool modem_acks = hardware_ack_links_.count(link) > 0;
  if (e.hops >= e.hop_limit) {
    ++stats_.hop_limit_dropped;
    spdlog::warn("route: message {}/{} for node {} dropped after {} hops (its limit: a routing loop?)", e.origin,
                 e.seq, e.destination, e.hops);
    if (modem_acks) owe_custody_receipt(link, from, e.identity(), true);
    return consumed(used);  // acknowledged: the loop ends here
  }
  if (e.ttl_s == 0) {
    ++stats_.expired_dropped;
    spdlog::warn("route: message {}/{} for node {} arrived with no ttl left: dropped", e.origin, e.seq,
                 e.destination);
    report_expired(e, now);
    if (modem_acks) owe_custody_receipt(link, from, e.identity(), true);
    return consumed(used);
  }
  if (auto it = pending_.find(e.identity()); it != pending_.end()) {
    // A resend while the first copy is being stored: ACKed only if that
    // store succeeds, as the first is.
    ++stats_.custody_copies;
    if (modem_acks) receipt_on_commit_[e.identity()] = {link, from};
    return taken_only_if(used, it->second);
  }
  if (holds(e.identity())) {
    ++stats_.custody_copies;  // a resend whose ACK (or receipt) was lost: ours already
    if (modem_acks) owe_custody_receipt(link, from, e.identity(), true);
    return consumed(used);
  }
  if (held() >= max_custody_) {
    ++stats_.custody_refused;
    // Once per burst: the previous hop resends every slot while it lasts.
    if (!refusing_) {
      spdlog::warn("route: custody of message {}/{} for node {} refused: {} held (routing.max_custody); the "
                   "previous hop keeps it{}",
                   e.origin, e.seq, e.destination, held(), modem_acks ? " (custody receipt: refused)" : "");
    }
    refusing_ = true;
    if (modem_acks) {
      // The modem ACKed it; the previous hop keeps it until our receipt.
      owe_custody_receipt(link, from, e.identity(), false);
      return consumed(used);
    }
    return taken_only_if(used, std::make_shared<std::atomic<bool>>(false));
  }
  refusing_ = false;
  if (modem_acks) receipt_on_commit_[e.identity()] = {link, from};
  ++e.hops;
  const MessageIdentity identity = e.identity();
  queue::JournalMessage record;
  record.type = custody_queue(e.value_tenths);
  record.payload = encode_envelope(e, envelope_id_);
  record.src = e.origin;
  record.dest = e.destination;
  record.submitted_at = now;
  record.ttl_s = e.ttl_s;
  auto taken = std::make_shared<std::atomic<bool>>(true);
  ++stats_.custody_taken;
  journal_into_custody(std::move(record), identity, taken);
  spdlog::debug("route: message {}/{} for node {} taken into custody (hop {})", e.origin, e.seq, e.destination,
                e.hops);
  return taken_only_if(used, taken);
}

queue::RoutedForm Forwarder::outgoing(const queue::Queue& queue, const queue::QueuedMessage& message,
                                      const queue::DataRequest& request, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  using Kind = queue::RoutedForm::Kind;
  const bool custody = is_custody(queue.type());
  const int32_t dest = message.record.dest;
  // Its modem ACKed it on the last offer; the next hop's custody receipt
  // is awaited (forwarder_custody.cpp). Before any other answer: the next
  // hop may hold a copy and pass it on, so it may not go again in any
  // form meanwhile, not even plain to a destination that became a
  // neighbour (its delivery would not be known as a copy there).
  if (awaiting_custody_receipt(queue, message, now)) return hold();
  if (!custody && (dest == queue::kBroadcast || dest == own_id_)) return {};
  std::optional<NextHop> next = table_.next_hop(dest, now);
  if (!next) return hold();  // waits for a route
  if (!custody && next->node == dest) {
    // A neighbour: plain DCCL. An earlier wrapped send's note is stale
    // now: a modem ACK of this plain frame must not hold it for a receipt.
    wrapped_.erase(message.record.id);
    offers_.erase(message.record.id);
    return {};
  }
  if (next->link != link_name(request.link)) return hold();
  Envelope e;
  if (custody) {
    std::optional<Envelope> held = held_envelope(message, envelope_id_);
    if (!held) return hold();  // cannot happen: we wrote it
    e = std::move(*held);
    // A receipt of ours (forwarder_receipts.cpp) takes its sequence from
    // its journal id, as a submitted message does, when it first goes.
    if (e.origin == own_id_ && starts_envelope(e.payload, envelope_id_)) {
      e.seq = static_cast<uint16_t>(message.record.id & 0xffff);
    }
  } else {
    if (message.encoded.empty() || message.encoded.size() > kMaxPayloadBytes) return hold();
    e.origin = static_cast<uint16_t>(own_id_);
    e.destination = static_cast<uint16_t>(dest);
    e.seq = static_cast<uint16_t>(message.record.id & 0xffff);
    e.hops = 1;
    e.hop_limit = static_cast<uint8_t>(hop_limit_);
    e.value_tenths = value_to_tenths(queue.policy().value_base);
    e.payload = message.encoded;
  }
  e.ttl_s = ttl_to_seconds(remaining_ttl(queue, message, now));
  queue::RoutedForm form;
  form.kind = Kind::kWrapped;
  form.bytes = encode_envelope(e, envelope_id_);
  form.next_hop = next->node;
  return form;
}

std::string Forwarder::waiting(const queue::Queue& queue, const queue::QueuedMessage& message) const {
  ACOMMS_ASSERT_CORE_THREAD();
  const int32_t dest = message.record.dest;
  if (auto h = held_for_receipt_.find(message.record.id); h != held_for_receipt_.end()) {
    return "awaiting the custody receipt of node " + std::to_string(h->second.next_hop);
  }
  if (!is_custody(queue.type()) && (dest == queue::kBroadcast || dest == own_id_)) return "";
  std::optional<NextHop> next = table_.next_hop(dest, clock_.now_seconds());
  if (!next) return "no route to node " + std::to_string(dest);
  // Its route leads through another node, but the envelope cannot carry it:
  // it waits for ever (until its ttl), without holding back others.
  if (!is_custody(queue.type()) && next->node != dest && message.encoded.size() > kMaxPayloadBytes) {
    return "too large for the routing envelope (" + std::to_string(message.encoded.size()) + " bytes, at most " +
           std::to_string(kMaxPayloadBytes) + ")";
  }
  return "";
}

// An end-to-end ack or expiry report in custody says so (queue ls).
std::string Forwarder::receipt_json(const std::string& payload) const {
  // Sealed or not (route/receipt_seal.h): its first bytes say which.
  std::optional<Receipt> receipt = decode_receipt(std::string_view(payload).substr(0, kReceiptBytes), envelope_id_);
  if (!receipt) return "";
  return ",\"receipt\":\"" + std::string(to_string(receipt->kind)) + "\",\"about_seq\":" + std::to_string(receipt->seq);
}

std::string Forwarder::custody_json(const queue::Queue& queue, const queue::QueuedMessage& message) const {
  if (!is_custody(queue.type())) return "";
  std::optional<Envelope> e = held_envelope(message, envelope_id_);
  if (!e) return "";
  return "{\"origin\":" + std::to_string(e->origin) + ",\"destination\":" + std::to_string(e->destination) +
         ",\"seq\":" + std::to_string(e->seq) + ",\"hops\":" + std::to_string(e->hops) + ",\"hop_limit\":" +
         std::to_string(e->hop_limit) + ",\"message_bytes\":" + std::to_string(e->payload.size()) +
         receipt_json(e->payload) + "}";
}

std::optional<queue::QueuePolicy> Forwarder::custody_policy(const std::string& type) const {
  if (!is_custody(type)) return std::nullopt;
  const std::string_view digits = std::string_view(type).substr(std::string_view(kCustodyQueuePrefix).size());
  unsigned tenths = 0;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), tenths);
  if (ec != std::errc() || end != digits.data() + digits.size() || tenths > 255) return std::nullopt;
  queue::QueuePolicy policy;
  policy.ack = true;
  policy.value_base = tenths / 10.0;
  policy.ttl_s = custody_ttl_s_;
  // Twice the bound: room, at restore, for what a modem-ACK link made a
  // node take over the bound before custody receipts (take_custody now
  // refuses at the bound on every link).
  policy.max_queue = max_custody_ * 2;
  policy.newest_first = false;  // forwarded in the order they came
  policy.on_full = queue::QueuePolicy::OnFull::kRefuseNew;
  return policy;
}

}  // namespace acomms::route
