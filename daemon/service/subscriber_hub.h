#pragma once
// Fans received messages out to Subscribe streams.
//
// The link must never wait for a client: publish() only appends to each
// matching subscriber's bounded buffer. A subscriber whose buffer is full has fallen behind for good (acoustic
// traffic is a few messages a minute; a full buffer means the client stopped
// reading), so it is ended with RESOURCE_EXHAUSTED instead of silently
// losing messages in the middle of its stream.
//
// Thread-safe: any thread may subscribe, read a subscription or close;
// publish() is called by one thread at a time, in seq order (below).

#include <grpcpp/support/status.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "acomms/v1/acomms.pb.h"

namespace acomms::service {

class Subscription {
 public:
  struct Filter {
    std::set<std::string> types;  // empty: all
    std::optional<int32_t> src;
  };
  Subscription(Filter filter, size_t capacity) : filter_(std::move(filter)), capacity_(capacity) {}

  bool wants(const v1::ReceivedMessage& message) const;

  // Called by the hub: adds a message, or ends the subscription when its
  // buffer is full.
  void offer(const v1::ReceivedMessage& message);
  // Ends the stream with `status` once what is buffered has been read
  // (OK-status ends are not used: a subscription lasts until cancelled).
  void end(grpc::Status status);

  // Waits up to `wait` for the next message. Returns it, or nullopt: then
  // ended() tells whether the stream is over (and why) or the wait timed out.
  std::optional<v1::ReceivedMessage> next(std::chrono::milliseconds wait);
  std::optional<grpc::Status> ended() const;

 private:
  const Filter filter_;
  const size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<v1::ReceivedMessage> buffer_;
  std::optional<grpc::Status> end_;
};

class SubscriberHub {
 public:
  // Messages a subscriber may have waiting before it is dropped.
  static constexpr size_t kDefaultCapacity = 1024;

  explicit SubscriberHub(size_t capacity = kDefaultCapacity) : capacity_(capacity) {}

  // Any thread. The subscription receives what is published from now on.
  // After close(), returns a subscription that has already ended.
  std::shared_ptr<Subscription> subscribe(Subscription::Filter filter);
  void unsubscribe(const std::shared_ptr<Subscription>& subscription);

  // Hands `message` to every subscriber that wants it. One thread at a
  // time, in seq order: the daemon calls it from the store writer's thread
  // once the message's seq is committed (see service/subscribe_rpc.cpp for
  // why), and it never waits for a client.
  void publish(const v1::ReceivedMessage& message);

  // Ends every subscription with UNAVAILABLE (the daemon is stopping).
  void close();

  size_t subscribers() const;
  uint64_t dropped_subscribers() const;

 private:
  const size_t capacity_;
  mutable std::mutex mutex_;
  std::vector<std::shared_ptr<Subscription>> subscribers_;
  bool closed_ = false;
  uint64_t dropped_ = 0;
};

}  // namespace acomms::service
