#include "queue/queue.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "queue/priority.h"

namespace acomms::queue {

Queue::Queue(std::string type, int dccl_id, QueuePolicy policy, double created_at)
    : type_(std::move(type)),
      dccl_id_(dccl_id),
      policy_(policy),
      last_sent_(created_at),
      next_expiry_(std::numeric_limits<double>::infinity()) {}

bool Queue::push(QueuedMessage message, std::optional<QueuedMessage>* dropped) {
  if (messages_.size() >= policy_.max_queue) {
    if (policy_.on_full == QueuePolicy::OnFull::kRefuseNew) return false;
    if (messages_.front().in_flight_frame != 0) forget_in_flight(messages_.front().record.id);
    *dropped = std::move(messages_.front());
    messages_.pop_front();
  }
  next_expiry_ = std::min(next_expiry_, message.record.submitted_at + ttl_of(message));
  messages_.push_back(std::move(message));
  note_size();
  return true;
}

double Queue::priority(double now) const {
  return dynamic_priority(policy_.value_base, policy_.ttl_s, now - last_sent_);
}

bool Queue::in_blackout(double now) const {
  return has_sent_ && now - last_sent_ < policy_.blackout_time_s;
}

const QueuedMessage* Queue::next_eligible() const {
  auto eligible = [](const QueuedMessage& m) { return m.in_flight_frame == 0; };
  if (policy_.newest_first) {
    auto it = std::find_if(messages_.rbegin(), messages_.rend(), eligible);
    return it == messages_.rend() ? nullptr : &*it;
  }
  auto it = std::find_if(messages_.begin(), messages_.end(), eligible);
  return it == messages_.end() ? nullptr : &*it;
}

std::deque<QueuedMessage>::iterator Queue::find(int64_t id) {
  auto it = std::lower_bound(messages_.begin(), messages_.end(), id,
                             [](const QueuedMessage& m, int64_t v) { return m.record.id < v; });
  return it != messages_.end() && it->record.id == id ? it : messages_.end();
}

void Queue::forget_in_flight(int64_t id) {
  in_flight_ids_.erase(std::remove(in_flight_ids_.begin(), in_flight_ids_.end(), id), in_flight_ids_.end());
}

void Queue::mark_sent(int64_t id, uint64_t frame_id, double now) {
  last_sent_ = now;
  has_sent_ = true;
  auto it = find(id);
  if (it == messages_.end()) {
    throw std::logic_error("queue " + type_ + ": no message " + std::to_string(id) + " to send");
  }
  if (frame_id != 0) {
    it->in_flight_frame = frame_id;
    in_flight_ids_.push_back(id);
    return;
  }
  messages_.erase(it);
  note_size();
}

namespace {

// Moves the messages matching `pred` out of `messages`, keeping the order
// of the rest.
template <typename Pred>
std::vector<QueuedMessage> extract(std::deque<QueuedMessage>& messages, Pred pred) {
  std::vector<QueuedMessage> out;
  auto keep = std::stable_partition(messages.begin(), messages.end(),
                                    [&](const QueuedMessage& m) { return !pred(m); });
  std::move(keep, messages.end(), std::back_inserter(out));
  messages.erase(keep, messages.end());
  return out;
}

}  // namespace

std::vector<QueuedMessage> Queue::take_acked(uint64_t frame_id,
                                             const std::function<bool(const QueuedMessage&)>& keep) {
  std::vector<QueuedMessage> acked;
  std::vector<int64_t> still_in_flight;
  for (int64_t id : in_flight_ids_) {
    auto it = find(id);
    if (it->in_flight_frame != frame_id) {
      still_in_flight.push_back(id);
      continue;
    }
    if (keep && keep(*it)) {
      it->in_flight_frame = 0;  // held: queued, not in flight, not acked
      continue;
    }
    acked.push_back(std::move(*it));
    messages_.erase(it);
  }
  in_flight_ids_ = std::move(still_in_flight);
  note_size();
  return acked;
}

std::vector<QueuedMessage> Queue::take_expired(double now) {
  if (now <= next_expiry_) return {};
  auto expired = extract(messages_, [&](const QueuedMessage& m) { return now - m.record.submitted_at > ttl_of(m); });
  next_expiry_ = std::numeric_limits<double>::infinity();
  for (const QueuedMessage& m : messages_) next_expiry_ = std::min(next_expiry_, m.record.submitted_at + ttl_of(m));
  for (const QueuedMessage& m : expired) {
    if (m.in_flight_frame != 0) forget_in_flight(m.record.id);
  }
  note_size();
  return expired;
}

std::optional<QueuedMessage> Queue::take(int64_t id) {
  auto taken = extract(messages_, [id](const QueuedMessage& m) { return m.record.id == id; });
  if (taken.empty()) return std::nullopt;
  if (taken.front().in_flight_frame != 0) forget_in_flight(id);
  note_size();
  return std::move(taken.front());
}

}  // namespace acomms::queue
