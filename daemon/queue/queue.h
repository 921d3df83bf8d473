#pragma once
// One queue: the messages of one DCCL type, in submission order, under that
// type's policy. Owned and used by the QueueManager on the core thread only
// (refuses_new() excepted).

#include <atomic>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "queue/queue_policy.h"
#include "queue/queued_message.h"

namespace acomms::queue {

class Queue {
 public:
  Queue(std::string type, int dccl_id, QueuePolicy policy, double created_at);

  const std::string& type() const { return type_; }
  int dccl_id() const { return dccl_id_; }
  const QueuePolicy& policy() const { return policy_; }
  size_t size() const { return messages_.size(); }
  size_t in_flight() const { return in_flight_ids_.size(); }
  double last_sent() const { return last_sent_; }
  const std::deque<QueuedMessage>& messages() const { return messages_; }

  // Adds a message. When the queue is full: with DROP_OLDEST the oldest
  // message is removed and returned in *dropped; with REFUSE_NEW nothing
  // changes and false is returned.
  bool push(QueuedMessage message, std::optional<QueuedMessage>* dropped);

  // Any thread: true while the queue is full and its policy is REFUSE_NEW,
  // so that a Submit can be refused before it is stored.
  bool refuses_new() const { return refuses_new_.load(std::memory_order_relaxed); }

  // P(t) = value_base * (t - t_last_sent) / ttl.
  double priority(double now) const;
  bool in_blackout(double now) const;

  // The message this queue would send next (newest or oldest first, per
  // policy), skipping those awaiting an ack; nullptr if none.
  const QueuedMessage* next_eligible() const;
  // The first message in that same order, not awaiting an ack, that
  // `sendable` accepts; nullptr if none. A gateway's queues hold messages
  // for many next hops: one that must wait (no route, another link) must
  // not hold back the ones behind it (frame_building.cpp).
  template <typename Pred>
  const QueuedMessage* first_eligible(Pred sendable) const {
    auto accept = [&](const QueuedMessage& m) { return m.in_flight_frame == 0 && sendable(m); };
    if (policy_.newest_first) {
      for (auto it = messages_.rbegin(); it != messages_.rend(); ++it) {
        if (accept(*it)) return &*it;
      }
      return nullptr;
    }
    for (const QueuedMessage& m : messages_) {
      if (accept(m)) return &m;
    }
    return nullptr;
  }

  // Marks a message sent at `now`: in flight in `frame_id` (awaiting its
  // ack) when frame_id != 0, else removed.
  void mark_sent(int64_t id, uint64_t frame_id, double now);

  // Removes and returns the messages in flight in `frame_id`, but those
  // `keep` says yes to (a routed message held for its custody receipt:
  // queue/routing.h), which stay queued, no longer in flight.
  std::vector<QueuedMessage> take_acked(uint64_t frame_id,
                                        const std::function<bool(const QueuedMessage&)>& keep = nullptr);
  // Makes every in-flight message eligible again, calling `released` for
  // each (before its frame id is cleared).
  template <typename Fn>
  void release_in_flight(Fn released) {
    for (int64_t id : in_flight_ids_) {
      QueuedMessage& m = *find(id);
      released(static_cast<const QueuedMessage&>(m));
      m.in_flight_frame = 0;
    }
    in_flight_ids_.clear();
  }
  // The same for the messages in flight in frames `released_frame` says
  // yes to.
  template <typename Pred, typename Fn>
  void release_in_flight_if(Pred released_frame, Fn released) {
    std::vector<int64_t> kept;
    for (int64_t id : in_flight_ids_) {
      QueuedMessage& m = *find(id);
      if (!released_frame(m.in_flight_frame)) {
        kept.push_back(id);
        continue;
      }
      released(static_cast<const QueuedMessage&>(m));
      m.in_flight_frame = 0;
    }
    in_flight_ids_ = std::move(kept);
  }
  // Removes and returns messages older than their ttl at `now`.
  std::vector<QueuedMessage> take_expired(double now);
  // Removes a message by id (cancel); nullopt if it is not here.
  std::optional<QueuedMessage> take(int64_t id);

  // The message with `id` (binary search: ids ascend); end() if absent.
  std::deque<QueuedMessage>::iterator find(int64_t id);

  double ttl_of(const QueuedMessage& message) const {
    return message.record.ttl_s > 0 ? message.record.ttl_s : policy_.ttl_s;
  }

 private:
  // After every change of size: keeps refuses_new() true to the queue.
  void note_size() {
    refuses_new_.store(policy_.on_full == QueuePolicy::OnFull::kRefuseNew && messages_.size() >= policy_.max_queue,
                       std::memory_order_relaxed);
  }
  void forget_in_flight(int64_t id);

  std::string type_;
  int dccl_id_;
  QueuePolicy policy_;
  // Until the first send, t_last_sent is the queue's creation time: a new
  // queue's priority grows from zero like any other, but it is not in blackout.
  double last_sent_;
  bool has_sent_ = false;
  // Submission order (ids ascending): the front is the oldest.
  std::deque<QueuedMessage> messages_;
  // Ids of the messages awaiting an ack, so that releasing or acking them
  // does not walk a queue of thousands.
  std::vector<int64_t> in_flight_ids_;
  // No message expires before this time: lets the expiry sweep, which runs
  // for every queue on every frame, cost nothing when nothing is due.
  double next_expiry_ = 0;
  std::atomic<bool> refuses_new_{false};
};

}  // namespace acomms::queue
