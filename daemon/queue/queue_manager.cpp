// The queues themselves: made per loaded type, brought back from the
// journal at start-up, fed by the steps of a submit, and emptied by expiry,
// Cancel and Flush, each change counted and logged as an event. Frame
// building, the receive side and its filter have files of their own.
#include "queue/queue_manager.h"

#include <google/protobuf/descriptor.h>
#include <spdlog/spdlog.h>

#include <set>

#include "core/core_thread.h"

namespace acomms::queue {
namespace {

namespace pb = google::protobuf;

const v1::QueueTypeConfig* type_config(const v1::QueueConfig& config, const std::string& type) {
  for (const auto& entry : config.type()) {
    if (entry.type() == type) return &entry;
  }
  return nullptr;
}

}  // namespace

std::string queue_full_text(const Queue& queue) {
  return "queue " + queue.type() + " is full (max_queue " + std::to_string(queue.policy().max_queue) +
         ") and refuses new messages";
}

QueueManager::QueueManager(const dccl::Codec& codec, const v1::QueueConfig& config, int32_t own_id,
                           const core::Clock& clock, MessageJournal& journal)
    : codec_(codec),
      config_(config),
      own_id_(own_id),
      promiscuous_(config.promiscuous()),
      clock_(clock),
      journal_(journal),
      // Frame ids only need to be unique; starting from the clock keeps them
      // unique across restarts too, so the event log never reuses one.
      next_frame_id_(static_cast<uint64_t>(clock.now_seconds() * 1e6)),
      receive_filter_(config) {
  std::set<std::string> configured;
  for (const auto& entry : config.type()) {
    if (!configured.insert(entry.type()).second) {
      throw std::invalid_argument("queue " + entry.type() + " is configured twice");
    }
    if (codec.find_type(entry.type()) == nullptr) {
      throw std::invalid_argument("queue " + entry.type() + " is configured but no such DCCL type is loaded");
    }
  }
  add_types();
}

std::vector<std::string> QueueManager::add_types() {
  double now = clock_.now_seconds();
  std::vector<std::string> added;
  for (const dccl::TypeInfo* info : codec_.types()) {
    if (info->omit_id) continue;  // without an id, a frame cannot say what it carries
    if (by_name_.count(info->name) > 0) continue;
    const v1::QueueTypeConfig* entry = type_config(config_, info->name);
    QueuePolicy policy = resolve_policy(entry ? entry->policy() : v1::QueuePolicy(), config_.defaults(),
                                        "queue " + info->name);
    MessageRoles roles(info->descriptor, entry ? entry->roles() : v1::QueueRoles());
    TypeState& state = by_id_.try_emplace(info->id).first->second;
    state.queue = std::make_unique<Queue>(info->name, info->id, policy, now);
    state.roles = std::move(roles);
    // A type may keep out of the filter: it drops repeats itself.
    const bool filtered = entry == nullptr || !entry->has_duplicate_filter() || entry->duplicate_filter();
    if (filtered) state.window_s = receive_filter_.add_type(info->name, policy.ttl_s, state.roles);
    by_name_[info->name] = &state;
    added.push_back(info->name);
  }
  return added;
}

void QueueManager::emit(TypeState& state, double now, const Change& change) {
  const QueueEventKind kind = change.kind;
  QueueStats& s = state.stats;
  switch (kind) {
    case QueueEventKind::kQueued: ++s.queued; break;
    case QueueEventKind::kSent: ++s.sent; break;
    case QueueEventKind::kAcked: ++s.acked; break;
    case QueueEventKind::kExpired: ++(change.remote ? s.expired_remote : s.expired); break;
    case QueueEventKind::kDropped: ++s.dropped; break;
    case QueueEventKind::kRetry: ++s.retried; break;
    case QueueEventKind::kReceived: ++s.received; break;
    case QueueEventKind::kPacket: break;  // never a message's (record_packet)
    case QueueEventKind::kDelivered: ++s.delivered; break;
  }
  QueueEvent event;
  event.kind = kind;
  event.time = now;
  event.type = state.queue->type();
  event.message_id = change.message.id;
  event.frame_id = change.frame_id;
  event.src = change.message.src;
  event.dest = change.message.dest;
  event.detail = change.detail;
  event.removes_message = change.removes_message;
  event.encoded = change.encoded;
  if (change.link_figures) event.link_figures.emplace(*change.link_figures);
  if (change.auth_sent_s) {
    event.auth_sent_s = change.auth_sent_s;
    event.auth_sender = change.auth_sender;
    event.auth_forget_before = auth_guard_.forget_before(now);
  }
  // Numbered here, on the core thread, so numbers follow the order messages
  // are passed on; the journal makes each durable with its event.
  if (kind == QueueEventKind::kReceived) {
    event.seq = ++last_received_seq_;
    event.routed = receiving_routed_;
  }
  // Losses are worth an operator's attention; the rest is routine.
  auto level = (kind == QueueEventKind::kDropped || kind == QueueEventKind::kExpired)
                   ? spdlog::level::warn
                   : spdlog::level::debug;
  if (spdlog::should_log(level)) {
    spdlog::log(level, "queue {}: message {} {}{}{}", event.type, event.message_id, to_string(kind),
                change.frame_id ? " (frame " + std::to_string(change.frame_id) + ")" : "",
                event.detail.empty() ? "" : ": " + event.detail);
  }
  if (!change.already_journaled) journal_.record(event);
}

void QueueManager::record_packet(int32_t src, int32_t dest, std::string link_figures) {
  ACOMMS_ASSERT_CORE_THREAD();
  QueueEvent event;
  event.kind = QueueEventKind::kPacket;
  event.time = clock_.now_seconds();
  event.src = src;
  event.dest = dest;
  event.link_figures = std::move(link_figures);
  journal_.record(event);
}

int64_t QueueManager::take_received_seq() {
  ACOMMS_ASSERT_CORE_THREAD();
  return ++last_received_seq_;
}

void QueueManager::authenticate(const std::string& type, double window_s) {
  auto it = by_name_.find(type);
  if (it == by_name_.end()) throw std::invalid_argument("auth.type " + type + ": no queue of that type");
  if (!codec_.authenticated(type)) {
    throw std::invalid_argument("auth.type " + type + ": the codec does not authenticate it");
  }
  auth_guard_.add_type(type, window_s);
  TypeState& state = *it->second;
  if (state.queue->policy().ttl_s > window_s) {
    throw std::invalid_argument(fmt::format("auth.type {}: window_s {} is shorter than the queue's ttl_s {}: a "
                                            "message queued that long would arrive stale; lengthen the window "
                                            "or shorten the ttl",
                                            type, window_s, state.queue->policy().ttl_s));
  }
  state.auth_window_s = window_s;
}

void QueueManager::restore() {
  double now = clock_.now_seconds();
  size_t restored = 0;
  last_received_seq_ = journal_.last_received_seq();
  for (JournalMessage& record : journal_.load()) {
    auto it = by_name_.find(record.type);
    QueuedMessage message;
    message.record = record;
    // Held in custody for another node (routed_queues.cpp): the stored
    // payload is the envelope, sent as it is.
    const bool held_for_others = routing_ != nullptr && routing_->custody_policy(record.type).has_value();
    if (TypeState* custody = held_for_others ? custody_state(record.type) : nullptr) {
      message.encoded = record.payload;
      std::optional<QueuedMessage> dropped;
      if (custody->queue->push(std::move(message), &dropped)) {
        ++restored;
      } else {
        emit(*custody, now, {.kind = QueueEventKind::kDropped, .message = record,
                             .detail = "custody queue full at restore", .removes_message = true});
      }
      continue;
    }
    if (it == by_name_.end() && !codec_.refusal(record.type).empty()) {
      // The type's definition still loads but this codec refuses the type
      // (one the reference DCCL refuses, or one using dynamic_conditions):
      // the user did not remove it, so the message stays stored for a
      // version or definition that can send it.
      spdlog::warn("queue: stored message {} of type {} kept in the store but not queued: {}", record.id,
                   record.type, codec_.refusal(record.type));
      continue;
    }
    if (it == by_name_.end()) {
      // No queue to put it in: log it against no type, and let it go.
      QueueEvent event;
      event.kind = QueueEventKind::kDropped;
      event.time = now;
      event.type = record.type;
      event.message_id = record.id;
      event.src = record.src;
      event.dest = record.dest;
      event.detail = "type no longer loaded";
      event.removes_message = true;
      spdlog::warn("queue: stored message {} of type {} dropped: type no longer loaded", record.id,
                   record.type);
      journal_.record(event);
      continue;
    }
    TypeState& state = *it->second;
    try {
      auto decoded = codec_.new_message(record.type);
      if (!decoded->ParseFromString(record.payload)) throw std::runtime_error("stored payload does not parse");
      message.encoded = codec_.encode(*decoded);
      if (const std::string* first = first_seal(record, message.encoded, now)) message.encoded = *first;
    } catch (const std::exception& e) {
      spdlog::warn("queue {}: stored message {} cannot be re-encoded: {}", record.type, record.id, e.what());
      emit(state, now, {.kind = QueueEventKind::kDropped, .message = record, .detail = "cannot re-encode",
                        .removes_message = true});
      continue;
    }
    std::optional<QueuedMessage> dropped;
    if (!state.queue->push(std::move(message), &dropped)) {
      emit(state, now, {.kind = QueueEventKind::kDropped, .message = record, .detail = "queue full at restore",
                        .removes_message = true});
      continue;
    }
    if (dropped) {
      emit(state, now, {.kind = QueueEventKind::kDropped, .message = dropped->record,
                        .detail = "queue full: oldest dropped", .removes_message = true});
    }
    ++restored;
  }
  spdlog::info("queue: {} message{} restored from the store", restored, restored == 1 ? "" : "s");
  receive_filter_.refill(journal_, now);
  auth_guard_.refill(journal_, now);
}

const std::string* QueueManager::first_seal(const JournalMessage& record, const std::string& resealed,
                                            double now) const {
  const dccl::MessageAuthenticator* authenticator = codec_.authenticator();
  if (record.sealed.empty() || authenticator == nullptr || !codec_.authenticated(record.type)) return nullptr;
  const size_t trailer = authenticator->trailer_bytes();
  // The same DCCL bytes (definition and crypto unchanged), a trailer of
  // today's length, and a key still accepted: otherwise the new seal goes.
  const bool same = record.sealed.size() == resealed.size() && resealed.size() >= trailer &&
                    record.sealed.compare(0, resealed.size() - trailer, resealed, 0, resealed.size() - trailer) == 0;
  if (!same || authenticator->verify(record.sealed, now, authenticator->sender(), nullptr) != dccl::AuthVerdict::kOk) {
    spdlog::info("queue {}: stored message {} sealed again at restore (its first seal no longer fits the type "
                 "or the keyring)",
                 record.type, record.id);
    return nullptr;
  }
  return &record.sealed;
}

double QueueManager::duplicate_window_s() const {
  ACOMMS_ASSERT_CORE_THREAD();
  return receive_filter_.longest_window_s();
}

double QueueManager::duplicate_window(const std::string& type) const {
  auto it = by_name_.find(type);
  if (it == by_name_.end()) throw UnknownTypeError("no queue for type " + type);
  return it->second->window_s;
}

void QueueManager::journal_new(const pb::Message& message, double ttl_s, Journaled journaled) const {
  auto queued = std::make_shared<QueuedMessage>(prepare_new(message, ttl_s));
  journal_.append(queued->record, [queued, journaled = std::move(journaled)](int64_t id, std::exception_ptr error) {
    queued->record.id = id;
    journaled(std::move(*queued), error);
  });
}

QueuedMessage QueueManager::prepare_new(const pb::Message& message, double ttl_s) const {
  const std::string& type = message.GetDescriptor()->full_name();
  auto it = by_name_.find(type);
  if (it == by_name_.end()) {
    throw UnknownTypeError(codec_.find_type(type) ? type + " has no id (omit_id) and cannot be queued"
                                                  : "no DCCL type " + type + " is loaded");
  }
  const TypeState& state = *it->second;
  // A resend after the receiver's window would be delivered again.
  if (state.window_s > 0 && ttl_s > state.window_s) {
    throw TtlTooLongError(fmt::format(
        "{}: ttl_s {} is longer than the queue's duplicate window of {} s (the longer of its ttl_s and "
        "queue.duplicate_window_s): a resend after that could be delivered twice; give at most {} or raise "
        "the type's ttl_s on every node",
        type, ttl_s, state.window_s, state.window_s));
  }
  // Its stamp is made now: a message still queued past the window arrives
  // stale.
  const double effective_ttl = ttl_s > 0 ? ttl_s : state.queue->policy().ttl_s;
  if (state.auth_window_s > 0 && effective_ttl > state.auth_window_s) {
    throw TtlTooLongError(fmt::format(
        "{}: ttl_s {} is longer than the type's authenticated window auth.type.window_s {} s: it would "
        "arrive stale; give at most {}",
        type, effective_ttl, state.auth_window_s, state.auth_window_s));
  }
  // Checked before anything is written, so that a refused Submit leaves no
  // trace in the store. Submits already being stored when the queue fills
  // are refused by accept() instead, after the fact.
  if (state.queue->refuses_new()) {
    state.refused.fetch_add(1, std::memory_order_relaxed);
    throw QueueFullError(queue_full_text(*state.queue));
  }
  double now = clock_.now_seconds();
  std::unique_ptr<pb::Message> filled = codec_.new_message(type);
  filled->CopyFrom(message);
  state.roles.fill_unset(filled.get(), own_id_, now);
  if (!filled->IsInitialized()) {
    throw dccl::encode_error(type + ": required field(s) missing: " + filled->InitializationErrorString());
  }

  QueuedMessage queued;
  queued.encoded = codec_.encode(*filled);  // throws dccl::Error in strict mode
  queued.record.type = type;
  queued.record.payload = filled->SerializeAsString();
  queued.record.src = state.roles.source(*filled);
  queued.record.dest = state.roles.destination(*filled);
  queued.record.submitted_at = now;
  queued.record.ttl_s = ttl_s;
  if (codec_.authenticated(type)) queued.record.sealed = queued.encoded;
  return queued;
}

bool QueueManager::accept(QueuedMessage message) {
  ACOMMS_ASSERT_CORE_THREAD();
  TypeState& state = *by_name_.at(message.record.type);
  double now = clock_.now_seconds();
  std::optional<QueuedMessage> dropped;
  JournalMessage record = message.record;
  if (!state.queue->push(std::move(message), &dropped)) {
    emit(state, now, {.kind = QueueEventKind::kDropped, .message = record,
                      .detail = "queue full: new message refused", .removes_message = true});
    return false;
  }
  // The journal logged "queued" with the message itself: count it only.
  emit(state, now, {.kind = QueueEventKind::kQueued, .message = record, .already_journaled = true});
  if (dropped) {
    emit(state, now, {.kind = QueueEventKind::kDropped, .message = dropped->record,
                      .detail = "queue full: oldest dropped", .removes_message = true});
  }
  return true;
}

void QueueManager::expire() {
  ACOMMS_ASSERT_CORE_THREAD();
  double now = clock_.now_seconds();
  for (auto& [id, state] : by_id_) {
    for (const QueuedMessage& m : state.queue->take_expired(now)) {
      std::string detail = routing_ != nullptr ? routing_->expired(*state.queue, m, now) : "";
      if (detail.empty()) detail = "ttl passed";
      emit(state, now, {.kind = QueueEventKind::kExpired, .message = m.record, .detail = detail,
                        .removes_message = true});
    }
  }
}

bool QueueManager::cancel(int64_t id, const std::string& reason) {
  ACOMMS_ASSERT_CORE_THREAD();
  double now = clock_.now_seconds();
  for (auto& [dccl_id, state] : by_id_) {
    if (std::optional<QueuedMessage> taken = state.queue->take(id)) {
      emit(state, now, {.kind = QueueEventKind::kDropped, .message = taken->record, .detail = reason,
                        .removes_message = true});
      return true;
    }
  }
  return false;
}

size_t QueueManager::flush(const std::string& type, const std::string& reason) {
  ACOMMS_ASSERT_CORE_THREAD();
  auto it = by_name_.find(type);
  if (it == by_name_.end()) throw UnknownTypeError("no queue for type " + type);
  TypeState& state = *it->second;
  std::vector<int64_t> ids;
  for (const QueuedMessage& message : state.queue->messages()) ids.push_back(message.record.id);
  double now = clock_.now_seconds();
  for (int64_t id : ids) {
    if (std::optional<QueuedMessage> taken = state.queue->take(id)) {
      emit(state, now, {.kind = QueueEventKind::kDropped, .message = taken->record, .detail = reason,
                        .removes_message = true});
    }
  }
  return ids.size();
}

const Queue* QueueManager::find_queue(const std::string& type) const {
  auto it = by_name_.find(type);
  return it == by_name_.end() ? nullptr : it->second->queue.get();
}

std::vector<const Queue*> QueueManager::queues() const {
  std::vector<const Queue*> out;
  for (const auto& [id, state] : by_id_) out.push_back(state.queue.get());
  return out;
}

QueueStats QueueManager::stats(const std::string& type) const {
  ACOMMS_ASSERT_CORE_THREAD();
  const TypeState& state = *by_name_.at(type);
  QueueStats stats = state.stats;
  stats.refused = state.refused.load(std::memory_order_relaxed);
  return stats;
}

}  // namespace acomms::queue
