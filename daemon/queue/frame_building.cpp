// Frame building: which queued messages go in a frame, and what an ack ends.
//
// The link gives each transmission a few small frames (tens to hundreds of
// bytes), far fewer than the messages waiting, so every place in a frame is
// contested. The contest, at time t, for each place: a queue takes part if
// it is out of blackout, has a message not awaiting an ack, that message
// fits in what is left of the frame, and its destination agrees with the
// transmission's. The highest P = value_base * (t - t_last_sent) / ttl
// wins; a tie goes to the queue that sent longest ago, then to the lower
// DCCL id. The winner's message is appended (DCCL messages self-delimit, so
// a frame needs no header of its own) and the contest runs again until
// nothing fits. A frame that asked for an ack keeps its messages in flight
// until on_ack(); without one, they are back in the next transmission's
// contest. With several links, "the next transmission" is the next of the
// same link (DataRequest::link), and a link may carry only what the node's
// choice of link lets it (DataRequest::may_carry). Core thread only.

#include <spdlog/spdlog.h>

#include <algorithm>
#include <set>
#include <vector>

#include "core/core_thread.h"
#include "queue/queue_manager.h"

namespace acomms::queue {

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
                                               int32_t dest, const DataRequest& request) {
  for (auto it = field.begin(); it != field.end();) {
    Queue& queue = *it->state->queue;
    const QueuedMessage* next = queue.next_eligible();
    // With routing (queue/routing.h) the message may go wrapped for a next
    // hop, or wait for a route; without, its form is itself.
    RoutedForm form;
    if (next != nullptr) form = routed_form(queue, *next, request, now);
    const size_t size = form.kind == RoutedForm::Kind::kWrapped ? form.bytes.size() : (next ? next->encoded.size() : 0);
    const int32_t to = form.kind == RoutedForm::Kind::kWrapped ? form.next_hop : (next ? next->record.dest : 0);
    bool takes_part = next != nullptr && form.kind != RoutedForm::Kind::kHold && !queue.in_blackout(now) &&
                      size <= room && (dest == kAnyDestination || to == dest || to == kBroadcast);
    // The link's cost is held against the type's standing before this
    // request (priority(now) at its start), not its P after winning a
    // place: a type worth the link's price fills the transmission.
    if (takes_part && request.may_carry) {
      takes_part = request.may_carry(queue.type(), next->record.dest, standing_[it->state]);
    }
    if (!takes_part) {
      it = field.erase(it);
      continue;
    }
    // The winner's standing after it sends: P = 0, sent now. Re-rank it.
    TypeState* winner = it->state;
    winner_form_ = std::move(form);
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
  // Whatever this link's last transmission carried and was not
  // acknowledged goes back into the contest: this is its next opportunity.
  release_in_flight(request.link);
  expire();
  standing_.clear();
  if (request.may_carry) {
    for (auto& [id, state] : by_id_) standing_[&state] = state.queue->priority(now);
  }

  std::vector<Frame> frames;
  int32_t dest = request.dest;
  for (uint32_t n = 0; n < request.max_num_frames; ++n) {
    Frame frame;
    frame.frame_id = next_frame_id_++;
    std::vector<Contender> field = contenders(now);
    while (TypeState* winner = contest(field, now, request.max_frame_bytes - frame.bytes.size(), dest, request)) {
      Queue& queue = *winner->queue;
      const QueuedMessage& next = *queue.next_eligible();
      const bool wrapped = winner_form_.kind == RoutedForm::Kind::kWrapped;
      if (dest == kAnyDestination) dest = wrapped ? winner_form_.next_hop : next.record.dest;
      // An ack needs a single addressee, a link that carries acks, and a
      // type that wants them; otherwise sending is the end of the message.
      bool awaits_ack = request.ack_requested && dest != kBroadcast && queue.policy().ack;
      frame.bytes += wrapped ? winner_form_.bytes : next.encoded;
      frame.message_ids.push_back(next.record.id);
      frame.ack_requested = frame.ack_requested || awaits_ack;
      emit(*winner, now, {.kind = QueueEventKind::kSent, .message = next.record, .frame_id = frame.frame_id,
                          .detail = awaits_ack ? "awaiting ack" : "", .removes_message = !awaits_ack});
      if (awaits_ack) {
        InFlightFrame& in_flight = in_flight_[frame.frame_id];
        in_flight.link = request.link;
        if (in_flight.types.empty() || in_flight.types.back() != winner) in_flight.types.push_back(winner);
      }
      queue.mark_sent(next.record.id, awaits_ack ? frame.frame_id : 0, now);  // `next` is gone after this
    }
    if (frame.bytes.empty()) break;
    frame.dest = dest;
    frames.push_back(std::move(frame));
  }
  if (piggyback_ != nullptr) add_piggyback(request, dest, now, &frames);
  return frames;
}

// The piggyback (queue/piggyback.h) comes after every contest is over: in
// what is left of the last frame, or, when the transmission may carry one
// more frame (no message was left that fitted) and goes anyway (a slot), in
// a frame of its own. Either way no queued message could have used the
// bytes it takes, and it never makes a paid link transmit.
void QueueManager::add_piggyback(const DataRequest& request, int32_t dest, double now, std::vector<Frame>* frames) {
  if (request.max_num_frames == 0) return;
  if (!frames->empty()) {
    Frame& last = frames->back();
    const size_t room = request.max_frame_bytes > last.bytes.size() ? request.max_frame_bytes - last.bytes.size() : 0;
    std::string bytes = piggyback_->take(request.link, room, now);
    if (!bytes.empty()) {
      last.bytes += bytes;
      return;
    }
    if (frames->size() >= request.max_num_frames) return;
  }
  if (!request.in_slot) return;
  std::string bytes = piggyback_->take(request.link, request.max_frame_bytes, now);
  if (bytes.empty()) return;
  Frame frame;
  frame.frame_id = next_frame_id_++;
  // Nobody in particular: a frame the queues had nothing for.
  frame.dest = dest == kAnyDestination ? kBroadcast : dest;
  frame.bytes = std::move(bytes);
  frames->push_back(std::move(frame));
}

void QueueManager::on_ack(uint64_t frame_id) {
  ACOMMS_ASSERT_CORE_THREAD();
  auto it = in_flight_.find(frame_id);
  if (it == in_flight_.end()) {
    spdlog::debug("queue: ack for frame {} that awaits none (late or duplicate)", frame_id);
    return;
  }
  double now = clock_.now_seconds();
  std::set<TypeState*> types(it->second.types.begin(), it->second.types.end());
  for (TypeState* state : types) {
    for (const QueuedMessage& m : state->queue->take_acked(frame_id)) {
      emit(*state, now, {.kind = QueueEventKind::kAcked, .message = m.record, .frame_id = frame_id,
                         .removes_message = true});
    }
  }
  in_flight_.erase(it);
}

void QueueManager::release_in_flight(int link) {
  ACOMMS_ASSERT_CORE_THREAD();
  std::set<uint64_t> frames;
  for (auto it = in_flight_.begin(); it != in_flight_.end();) {
    if (it->second.link != link) {
      ++it;
      continue;
    }
    frames.insert(it->first);
    it = in_flight_.erase(it);
  }
  if (frames.empty()) return;
  double now = clock_.now_seconds();
  // By type in DCCL order, as a single link always released them.
  for (auto& [id, state] : by_id_) {
    state.queue->release_in_flight_if([&](uint64_t frame) { return frames.count(frame) > 0; },
                                      [&](const QueuedMessage& m) {
                                        emit(state, now, {.kind = QueueEventKind::kRetry, .message = m.record,
                                                          .frame_id = m.in_flight_frame,
                                                          .detail = "not acknowledged"});
                                      });
  }
}

}  // namespace acomms::queue
