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
// choice of link lets it (DataRequest::may_carry). On a gateway (routing
// set) "its message" is the first in its order that may go now: a message
// waiting for a route, or for another link or next hop, is passed over,
// never a block on the ones behind it. Core thread only.

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
    RoutedForm form;
    // Whether `m` may take this place: with routing (queue/routing.h) it
    // may go wrapped for a next hop, or wait for a route; without, its form
    // is itself. `to` is whom the transmission carries it to: the next hop
    // of a wrapped message, not its final destination.
    auto sendable = [&](const QueuedMessage& m) {
      RoutedForm candidate = routed_form(queue, m, request, now);
      if (candidate.kind == RoutedForm::Kind::kHold) return false;
      const bool wrapped = candidate.kind == RoutedForm::Kind::kWrapped;
      const size_t size = wrapped ? candidate.bytes.size() : m.encoded.size();
      const int32_t to = wrapped ? candidate.next_hop : m.record.dest;
      if (size > room || !(dest == kAnyDestination || to == dest || to == kBroadcast)) return false;
      // The link's cost is held against the type's standing before this
      // request (priority(now) at its start), not its P after winning a
      // place: a type worth the link's price fills the transmission.
      if (request.may_carry && !request.may_carry(queue.type(), to, standing_[it->state])) return false;
      form = std::move(candidate);
      return true;
    };
    const QueuedMessage* chosen = nullptr;
    if (!queue.in_blackout(now)) {
      if (routing_ != nullptr) {
        // A gateway's queue holds messages for many next hops and links:
        // one that must wait (no route, another link, another next hop)
        // never blocks a sendable one behind it.
        chosen = queue.first_eligible(sendable);
      } else if (const QueuedMessage* next = queue.next_eligible(); next != nullptr && sendable(*next)) {
        chosen = next;
      }
    }
    if (chosen == nullptr) {
      it = field.erase(it);
      continue;
    }
    // The winner's standing after it sends: P = 0, sent now. Re-rank it.
    TypeState* winner = it->state;
    winner_form_ = std::move(form);
    winner_id_ = chosen->record.id;
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
    for (auto& [id, state] : by_id_) {
      // A message in custody was judged worth sending by its origin's
      // marketplace; against a link's cost it stands at its own value
      // (value_base), not at its custody queue's P, which restarts at 0
      // on every send and would keep it off any link that costs.
      const double p = state.queue->priority(now);
      standing_[&state] = state.custody ? std::max(p, state.queue->policy().value_base) : p;
    }
  }

  std::vector<Frame> frames;
  int32_t dest = request.dest;
  for (uint32_t n = 0; n < request.max_num_frames; ++n) {
    Frame frame;
    frame.frame_id = next_frame_id_++;
    std::vector<Contender> field = contenders(now);
    // What routing owes on this link (custody receipts, queue/routing.h):
    // its room is kept before the contest, its bytes go after the messages.
    std::string owed;
    if (routing_ != nullptr && n == 0) {
      owed = routing_->owed_on(request.link, request.dest, request.max_frame_bytes, now);
    }
    while (TypeState* winner =
               contest(field, now, request.max_frame_bytes - owed.size() - frame.bytes.size(), dest, request)) {
      Queue& queue = *winner->queue;
      const QueuedMessage& next = *queue.find(winner_id_);
      const bool wrapped = winner_form_.kind == RoutedForm::Kind::kWrapped;
      if (dest == kAnyDestination) dest = wrapped ? winner_form_.next_hop : next.record.dest;
      // An ack needs a single addressee, a link that carries acks, and a
      // type that wants them; otherwise sending is the end of the message.
      bool awaits_ack = request.ack_requested && dest != kBroadcast && queue.policy().ack;
      frame.bytes += wrapped ? winner_form_.bytes : next.encoded;
      frame.message_ids.push_back(next.record.id);
      frame.ack_requested = frame.ack_requested || awaits_ack;
      std::string detail = awaits_ack ? "awaiting ack" : "";
      if (wrapped) {
        // "to node 3 through node 2", then the ack it awaits.
        std::string route = routing_->on_sent(queue, next, winner_form_, now);
        detail = detail.empty() ? route : route + ", " + detail;
      }
      emit(*winner, now, {.kind = QueueEventKind::kSent, .message = next.record, .frame_id = frame.frame_id,
                          .detail = detail, .removes_message = !awaits_ack});
      if (awaits_ack) {
        InFlightFrame& in_flight = in_flight_[frame.frame_id];
        in_flight.link = request.link;
        if (in_flight.types.empty() || in_flight.types.back() != winner) in_flight.types.push_back(winner);
      }
      queue.mark_sent(next.record.id, awaits_ack ? frame.frame_id : 0, now);  // `next` is gone after this
    }
    frame.bytes += owed;
    if (frame.bytes.empty()) break;
    // A frame of owed bytes only is for whoever hears it, and so is the
    // rest of its transmission: one transmission has one destination (its
    // first frame's, link_controller.cpp), so no later frame may take a
    // unicast message that would await an ACK that transmission never asks
    // for (it would be sent again, and a type without duplicate_filter
    // delivered twice). Unicast messages go in the next transmission.
    if (dest == kAnyDestination) dest = kBroadcast;
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
  const int link = it->second.link;
  for (TypeState* state : types) {
    // A routed message the link's modem ACKed may stay, held for the next
    // hop's custody receipt (queue/routing.h): routing ends it later.
    auto keep = [&](const QueuedMessage& m) {
      return routing_ != nullptr && routing_->keeps_after_ack(*state->queue, m, link, now);
    };
    for (const QueuedMessage& m : state->queue->take_acked(frame_id, keep)) {
      const std::string detail = routing_ != nullptr ? routing_->acked_detail(*state->queue, m) : "";
      emit(*state, now, {.kind = QueueEventKind::kAcked, .message = m.record, .frame_id = frame_id,
                         .detail = detail, .removes_message = true});
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
