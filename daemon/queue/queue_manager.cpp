#include "queue/queue_manager.h"

#include <cmath>

#include <google/protobuf/descriptor.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <chrono>
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
      duplicate_filter_(config.has_duplicate_window_s() ? config.duplicate_window_s() : 300) {
  if (!(config.duplicate_window_s() >= 0) || !std::isfinite(config.duplicate_window_s())) {
    throw std::invalid_argument("queue.duplicate_window_s must be 0 (off) or a positive number of seconds");
  }
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
    by_name_[info->name] = &state;
    added.push_back(info->name);
  }
  return added;
}

void QueueManager::emit(QueueEventKind kind, TypeState& state, const JournalMessage& record, double now,
                        uint64_t frame_id, const char* detail, bool removes, bool journaled,
                        std::string_view encoded) {
  QueueStats& s = state.stats;
  switch (kind) {
    case QueueEventKind::kQueued: ++s.queued; break;
    case QueueEventKind::kSent: ++s.sent; break;
    case QueueEventKind::kAcked: ++s.acked; break;
    case QueueEventKind::kExpired: ++s.expired; break;
    case QueueEventKind::kDropped: ++s.dropped; break;
    case QueueEventKind::kRetry: ++s.retried; break;
    case QueueEventKind::kReceived: ++s.received; break;
  }
  QueueEvent event;
  event.kind = kind;
  event.time = now;
  event.type = state.queue->type();
  event.message_id = record.id;
  event.frame_id = frame_id;
  event.src = record.src;
  event.dest = record.dest;
  event.detail = detail;
  event.removes_message = removes;
  event.encoded = encoded;
  // Losses are worth an operator's attention; the rest is routine.
  auto level = (kind == QueueEventKind::kDropped || kind == QueueEventKind::kExpired)
                   ? spdlog::level::warn
                   : spdlog::level::debug;
  if (spdlog::should_log(level)) {
    spdlog::log(level, "queue {}: message {} {}{}{}", event.type, event.message_id, to_string(kind),
                frame_id ? " (frame " + std::to_string(frame_id) + ")" : "",
                event.detail.empty() ? "" : ": " + event.detail);
  }
  if (!journaled) journal_.record(event);
}

void QueueManager::restore() {
  double now = clock_.now_seconds();
  size_t restored = 0;
  for (JournalMessage& record : journal_.load()) {
    auto it = by_name_.find(record.type);
    QueuedMessage message;
    message.record = record;
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
      QueueEvent event{QueueEventKind::kDropped, now, record.type, record.id, 0, record.src, record.dest,
                       "type no longer loaded", true, {}};
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
    } catch (const std::exception& e) {
      spdlog::warn("queue {}: stored message {} cannot be re-encoded: {}", record.type, record.id, e.what());
      emit(QueueEventKind::kDropped, state, record, now, 0, "cannot re-encode", true);
      continue;
    }
    std::optional<QueuedMessage> dropped;
    if (!state.queue->push(std::move(message), &dropped)) {
      emit(QueueEventKind::kDropped, state, record, now, 0, "queue full at restore", true);
      continue;
    }
    if (dropped) emit(QueueEventKind::kDropped, state, dropped->record, now, 0, "queue full: oldest dropped", true);
    ++restored;
  }
  spdlog::info("queue: {} message{} restored from the store", restored, restored == 1 ? "" : "s");

  // A sender whose ACK was lost while this node was down sends again; what
  // was passed on before the restart must still count as seen.
  if (duplicate_filter_.window_s() > 0) {
    std::vector<QueueEvent> received = journal_.received_since(now - duplicate_filter_.window_s());
    for (const QueueEvent& event : received) duplicate_filter_.remember(event.src, event.encoded, event.time);
    spdlog::info("queue: {} message{} received in the last {} s remembered, so that retransmissions of them "
                 "are not passed on again", received.size(), received.size() == 1 ? "" : "s",
                 duplicate_filter_.window_s());
  }
}

QueuedMessage QueueManager::journal_new(const pb::Message& message, double ttl_s) const {
  QueuedMessage queued = prepare_new(message, ttl_s);
  queued.record.id = journal_.append(queued.record);
  return queued;
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
  return queued;
}

bool QueueManager::accept(QueuedMessage message) {
  ACOMMS_ASSERT_CORE_THREAD();
  TypeState& state = *by_name_.at(message.record.type);
  double now = clock_.now_seconds();
  std::optional<QueuedMessage> dropped;
  JournalMessage record = message.record;
  if (!state.queue->push(std::move(message), &dropped)) {
    emit(QueueEventKind::kDropped, state, record, now, 0, "queue full: new message refused", true);
    return false;
  }
  // The journal logged "queued" with the message itself: count it only.
  emit(QueueEventKind::kQueued, state, record, now, 0, "", false, /*journaled=*/true);
  if (dropped) emit(QueueEventKind::kDropped, state, dropped->record, now, 0, "queue full: oldest dropped", true);
  return true;
}

void QueueManager::expire() {
  ACOMMS_ASSERT_CORE_THREAD();
  double now = clock_.now_seconds();
  for (auto& [id, state] : by_id_) {
    for (const QueuedMessage& m : state.queue->take_expired(now)) {
      emit(QueueEventKind::kExpired, state, m.record, now, 0, "ttl passed", true);
    }
  }
}

// A queue in the contest for one frame, with its standing at the frame's
// time. Within one frame the time is fixed, so priorities change only for a
// queue that wins (its P drops to 0), and a queue that cannot take part now
// (nothing eligible, out of room, wrong destination, blackout) cannot later
// in the same frame either: room only shrinks and the destination only
// narrows. So the field is ranked once per frame and losers leave it for
// good, instead of every queue being re-examined for every message.
struct QueueManager::Contender {
  double priority;
  double last_sent;
  int dccl_id;
  TypeState* state;

  // Highest P first; ties to the queue that sent longest ago, then the
  // lower DCCL id.
  bool operator<(const Contender& other) const {
    if (priority != other.priority) return priority > other.priority;
    if (last_sent != other.last_sent) return last_sent < other.last_sent;
    return dccl_id < other.dccl_id;
  }
};

std::vector<QueueManager::Contender> QueueManager::contenders(double now) {
  std::vector<Contender> field;
  field.reserve(by_id_.size());
  for (auto& [id, state] : by_id_) {
    const Queue& queue = *state.queue;
    if (queue.size() == queue.in_flight() || queue.in_blackout(now)) continue;
    field.push_back({queue.priority(now), queue.last_sent(), id, &state});
  }
  std::sort(field.begin(), field.end());
  return field;
}

QueueManager::TypeState* QueueManager::contest(std::vector<Contender>& field, double now, size_t room,
                                               int32_t dest) {
  for (auto it = field.begin(); it != field.end();) {
    Queue& queue = *it->state->queue;
    const QueuedMessage* next = queue.next_eligible();
    bool takes_part = next != nullptr && !queue.in_blackout(now) && next->encoded.size() <= room &&
                      (dest == kAnyDestination || next->record.dest == dest || next->record.dest == kBroadcast);
    if (!takes_part) {
      it = field.erase(it);
      continue;
    }
    // The winner's standing after it sends: P = 0, sent now. Re-rank it.
    TypeState* winner = it->state;
    Contender after{0.0, now, it->dccl_id, winner};
    field.erase(it);
    field.insert(std::upper_bound(field.begin(), field.end(), after), after);
    return winner;
  }
  return nullptr;
}

std::vector<Frame> QueueManager::build_frames(const DataRequest& request) {
  ACOMMS_ASSERT_CORE_THREAD();
  double now = clock_.now_seconds();
  // Whatever the last transmission carried and was not acknowledged goes
  // back into the contest: this is its next opportunity.
  for (auto& [id, state] : by_id_) {
    state.queue->release_in_flight([&](const QueuedMessage& m) {
      emit(QueueEventKind::kRetry, state, m.record, now, m.in_flight_frame, "not acknowledged", false);
    });
  }
  in_flight_.clear();
  expire();

  std::vector<Frame> frames;
  int32_t dest = request.dest;
  for (uint32_t n = 0; n < request.max_num_frames; ++n) {
    Frame frame;
    frame.frame_id = next_frame_id_++;
    std::vector<Contender> field = contenders(now);
    while (TypeState* winner = contest(field, now, request.max_frame_bytes - frame.bytes.size(), dest)) {
      Queue& queue = *winner->queue;
      const QueuedMessage& next = *queue.next_eligible();
      if (dest == kAnyDestination) dest = next.record.dest;
      // An ack needs a single addressee, a link that carries acks, and a
      // type that wants them; otherwise sending is the end of the message.
      bool awaits_ack = request.ack_requested && dest != kBroadcast && queue.policy().ack;
      frame.bytes += next.encoded;
      frame.message_ids.push_back(next.record.id);
      frame.ack_requested = frame.ack_requested || awaits_ack;
      emit(QueueEventKind::kSent, *winner, next.record, now, frame.frame_id, awaits_ack ? "awaiting ack" : "",
           !awaits_ack);
      if (awaits_ack) {
        auto& types = in_flight_[frame.frame_id];
        if (types.empty() || types.back() != winner) types.push_back(winner);
      }
      queue.mark_sent(next.record.id, awaits_ack ? frame.frame_id : 0, now);  // `next` is gone after this
    }
    if (frame.bytes.empty()) break;
    frame.dest = dest;
    frames.push_back(std::move(frame));
  }
  return frames;
}

void QueueManager::on_ack(uint64_t frame_id) {
  ACOMMS_ASSERT_CORE_THREAD();
  auto it = in_flight_.find(frame_id);
  if (it == in_flight_.end()) {
    spdlog::debug("queue: ack for frame {} that awaits none (late or duplicate)", frame_id);
    return;
  }
  double now = clock_.now_seconds();
  std::set<TypeState*> types(it->second.begin(), it->second.end());
  for (TypeState* state : types) {
    for (const QueuedMessage& m : state->queue->take_acked(frame_id)) {
      emit(QueueEventKind::kAcked, *state, m.record, now, frame_id, "", true);
    }
  }
  in_flight_.erase(it);
}

bool QueueManager::cancel(int64_t id, const std::string& reason) {
  ACOMMS_ASSERT_CORE_THREAD();
  double now = clock_.now_seconds();
  for (auto& [dccl_id, state] : by_id_) {
    if (std::optional<QueuedMessage> taken = state.queue->take(id)) {
      emit(QueueEventKind::kDropped, state, taken->record, now, 0, reason.c_str(), true);
      return true;
    }
  }
  return false;
}

std::vector<ReceivedMessage> QueueManager::receive(std::string_view frame, int32_t transmission_src) {
  ACOMMS_ASSERT_CORE_THREAD();
  double now = clock_.now_seconds();
  std::vector<ReceivedMessage> out;
  size_t offset = 0;
  while (offset < frame.size()) {
    std::string_view rest = frame.substr(offset);
    try {
      const dccl::TypeInfo* info = codec_.find_id(codec_.id_of(rest));
      if (info == nullptr) throw dccl::decode_error("unknown DCCL id " + std::to_string(codec_.id_of(rest)));
      size_t used = 0;
      ReceivedMessage received;
      received.message = codec_.decode_as(info->name, rest, &used);
      if (used == 0) throw dccl::decode_error(info->name + " used no bytes");
      offset += used;
      received.type = info->name;
      received.time = now;
      auto state_it = by_name_.find(info->name);
      if (state_it == by_name_.end()) continue;
      TypeState& state = *state_it->second;
      received.dest = state.roles.destination(*received.message);
      int32_t src = state.roles.source(*received.message);
      received.src = src >= 0 ? src : transmission_src;
      if (!promiscuous_ && received.dest != own_id_ && received.dest != kBroadcast) {
        spdlog::debug("queue {}: received message for node {}, not for us", info->name, received.dest);
        continue;
      }
      received.encoded.assign(rest.substr(0, used));
      if (duplicate_filter_.seen(received.src, received.encoded, now)) {
        ++duplicates_;
        spdlog::info("queue {}: retransmission from {} not passed on again", info->name, received.src);
        continue;
      }
      JournalMessage as_event;
      as_event.src = received.src;
      as_event.dest = received.dest;
      emit(QueueEventKind::kReceived, state, as_event, now, 0, "", false, false, received.encoded);
      out.push_back(std::move(received));
    } catch (const dccl::Error& e) {
      // DCCL has no length fields: after bytes that do not decode, nothing
      // later in the frame can be found.
      ++malformed_frames_;
      spdlog::warn("queue: received frame from {} undecodable at byte {} of {} ({}): rest dropped",
                   transmission_src, offset, frame.size(), e.what());
      break;
    }
  }
  return out;
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
      emit(QueueEventKind::kDropped, state, taken->record, now, 0, reason.c_str(), true);
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
