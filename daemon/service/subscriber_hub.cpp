#include "service/subscriber_hub.h"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace acomms::service {

bool Subscription::wants(const v1::ReceivedMessage& message) const {
  if (filter_.src && *filter_.src != message.src()) return false;
  return filter_.types.empty() || filter_.types.count(message.type()) > 0;
}

void Subscription::offer(const v1::ReceivedMessage& message) {
  {
    std::lock_guard lock(mutex_);
    if (end_) return;
    if (buffer_.size() >= capacity_) {
      end_ = grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                          "subscriber too slow: " + std::to_string(capacity_) +
                              " messages waiting unread; subscription dropped (subscribe again; "
                              "missed messages are in the event log)");
      buffer_.clear();  // what it has not read is lost to it either way: free the memory now
    } else {
      buffer_.push_back(message);
    }
  }
  ready_.notify_one();
}

void Subscription::end(grpc::Status status) {
  {
    std::lock_guard lock(mutex_);
    if (!end_) end_ = std::move(status);
  }
  ready_.notify_one();
}

std::optional<v1::ReceivedMessage> Subscription::next(std::chrono::milliseconds wait) {
  std::unique_lock lock(mutex_);
  ready_.wait_for(lock, wait, [&] { return !buffer_.empty() || end_.has_value(); });
  if (buffer_.empty()) return std::nullopt;
  v1::ReceivedMessage message = std::move(buffer_.front());
  buffer_.pop_front();
  return message;
}

std::optional<grpc::Status> Subscription::ended() const {
  std::lock_guard lock(mutex_);
  return end_;
}

std::shared_ptr<Subscription> SubscriberHub::subscribe(Subscription::Filter filter) {
  auto subscription = std::make_shared<Subscription>(std::move(filter), capacity_);
  std::lock_guard lock(mutex_);
  if (closed_) {
    subscription->end(grpc::Status(grpc::StatusCode::UNAVAILABLE, "acommsd is stopping"));
  } else {
    subscribers_.push_back(subscription);
  }
  return subscription;
}

void SubscriberHub::unsubscribe(const std::shared_ptr<Subscription>& subscription) {
  std::lock_guard lock(mutex_);
  subscribers_.erase(std::remove(subscribers_.begin(), subscribers_.end(), subscription), subscribers_.end());
}

void SubscriberHub::publish(const v1::ReceivedMessage& message) {
  std::lock_guard lock(mutex_);
  // Subscribers that were ended (too slow) leave the list here, on the
  // next message, so the publishing thread never waits for their stream to close.
  auto gone = std::remove_if(subscribers_.begin(), subscribers_.end(), [&](const auto& subscription) {
    if (subscription->wants(message)) subscription->offer(message);
    if (!subscription->ended()) return false;
    ++dropped_;
    spdlog::warn("subscribe: a subscriber fell {} messages behind and was dropped", capacity_);
    return true;
  });
  subscribers_.erase(gone, subscribers_.end());
}

void SubscriberHub::close() {
  std::lock_guard lock(mutex_);
  closed_ = true;
  for (auto& subscription : subscribers_) {
    subscription->end(grpc::Status(grpc::StatusCode::UNAVAILABLE, "acommsd is stopping"));
  }
  subscribers_.clear();
}

size_t SubscriberHub::subscribers() const {
  std::lock_guard lock(mutex_);
  return subscribers_.size();
}

uint64_t SubscriberHub::dropped_subscribers() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace acomms::service
