// SubscriberHub and Subscription (daemon/service/subscriber_hub.h): filters
// by type and source, order, a subscriber that stops reading is ended with
// RESOURCE_EXHAUSTED and dropped without holding up publish() or anyone
// else, close() ends everything with UNAVAILABLE, unsubscribe removes.

#include "service/subscriber_hub.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <string>
#include <thread>
#include <vector>

namespace acomms::service {
namespace {

using namespace std::chrono_literals;

v1::ReceivedMessage received(const std::string& type, int32_t src, double time = 0) {
  v1::ReceivedMessage message;
  message.set_type(type);
  message.set_src(src);
  message.set_dest(0);
  message.set_receive_time(time);
  return message;
}

// Everything the subscription has buffered now, as "type/src" strings.
std::vector<std::string> drain(Subscription& subscription) {
  std::vector<std::string> out;
  while (auto message = subscription.next(0ms)) {
    out.push_back(message->type() + "/" + std::to_string(message->src()));
  }
  return out;
}

using Strings = std::vector<std::string>;

TEST(SubscriberHubTest, FiltersByTypesAndSource) {
  SubscriberHub hub(64);
  auto all = hub.subscribe({});
  auto status_only = hub.subscribe({{"t.Status"}, std::nullopt});
  auto two_types = hub.subscribe({{"t.Status", "t.Command"}, std::nullopt});
  auto from_four = hub.subscribe({{}, 4});
  auto status_from_four = hub.subscribe({{"t.Status"}, 4});
  EXPECT_EQ(hub.subscribers(), 5u);

  hub.publish(received("t.Status", 4));
  hub.publish(received("t.Command", 4));
  hub.publish(received("t.Status", 5));
  hub.publish(received("t.Ctd", 4));
  hub.publish(received("t.Ctd", 5));

  EXPECT_EQ(drain(*all), (Strings{"t.Status/4", "t.Command/4", "t.Status/5", "t.Ctd/4", "t.Ctd/5"}));
  EXPECT_EQ(drain(*status_only), (Strings{"t.Status/4", "t.Status/5"}));
  EXPECT_EQ(drain(*two_types), (Strings{"t.Status/4", "t.Command/4", "t.Status/5"}));
  EXPECT_EQ(drain(*from_four), (Strings{"t.Status/4", "t.Command/4", "t.Ctd/4"}));
  EXPECT_EQ(drain(*status_from_four), (Strings{"t.Status/4"}));
  for (const auto& s : {all, status_only, two_types, from_four, status_from_four}) {
    EXPECT_FALSE(s->ended().has_value());
  }
}

TEST(SubscriberHubTest, WantsAppliesTheFilter) {
  Subscription subscription({{"t.A"}, 2}, 4);
  EXPECT_TRUE(subscription.wants(received("t.A", 2)));
  EXPECT_FALSE(subscription.wants(received("t.A", 3)));
  EXPECT_FALSE(subscription.wants(received("t.B", 2)));
  Subscription src_zero({{}, 0}, 4);  // src 0 is a real filter, not "any"
  EXPECT_TRUE(src_zero.wants(received("t.B", 0)));
  EXPECT_FALSE(src_zero.wants(received("t.B", 1)));
}

TEST(SubscriberHubTest, MessagesArriveInPublishOrder) {
  SubscriberHub hub(1000);
  auto subscription = hub.subscribe({});
  for (int i = 0; i < 500; ++i) hub.publish(received("t.Status", i % 7, i));
  for (int i = 0; i < 500; ++i) {
    auto message = subscription->next(0ms);
    ASSERT_TRUE(message.has_value()) << "message " << i << " missing";
    EXPECT_EQ(message->receive_time(), i);
    EXPECT_EQ(message->src(), i % 7);
  }
  EXPECT_FALSE(subscription->next(0ms).has_value());
  EXPECT_FALSE(subscription->ended().has_value()) << "an empty buffer is not the end";
}

TEST(SubscriberHubTest, ReadersOnOtherThreadsGetEveryMessageInOrder) {
  SubscriberHub hub(100000);
  auto subscription = hub.subscribe({});
  constexpr int kCount = 20000;
  auto reader = std::async(std::launch::async, [&] {
    std::vector<double> times;
    while (times.size() < static_cast<size_t>(kCount)) {
      auto message = subscription->next(30s);
      if (!message) break;
      times.push_back(message->receive_time());
    }
    return times;
  });
  for (int i = 0; i < kCount; ++i) hub.publish(received("t.Status", 1, i));
  ASSERT_EQ(reader.wait_for(60s), std::future_status::ready);
  std::vector<double> times = reader.get();
  ASSERT_EQ(times.size(), static_cast<size_t>(kCount));
  for (int i = 0; i < kCount; ++i) ASSERT_EQ(times[i], i);
}

TEST(SubscriberHubTest, AWaitingReaderIsWokenByAPublish) {
  SubscriberHub hub(8);
  auto subscription = hub.subscribe({});
  auto reader = std::async(std::launch::async, [&] { return subscription->next(30s); });
  hub.publish(received("t.Status", 9, 42));
  ASSERT_EQ(reader.wait_for(30s), std::future_status::ready);
  auto message = reader.get();
  ASSERT_TRUE(message.has_value());
  EXPECT_EQ(message->receive_time(), 42);
}

TEST(SubscriberHubTest, ASubscriberThatFallsBehindIsEndedAndDroppedOthersGetEverything) {
  constexpr size_t kCapacity = 4;
  SubscriberHub hub(kCapacity);
  auto slow = hub.subscribe({});
  auto fast = hub.subscribe({});
  auto other_type = hub.subscribe({{"t.Other"}, std::nullopt});  // wants none of them: never full
  std::vector<double> fast_got;
  for (int i = 0; i < 20; ++i) {
    hub.publish(received("t.Status", 1, i));
    while (auto message = fast->next(0ms)) fast_got.push_back(message->receive_time());
    if (static_cast<size_t>(i) < kCapacity) {
      EXPECT_FALSE(slow->ended().has_value()) << "ended with only " << i + 1 << " messages waiting";
    }
  }
  std::vector<double> expected;
  for (int i = 0; i < 20; ++i) expected.push_back(i);
  EXPECT_EQ(fast_got, expected);
  EXPECT_FALSE(fast->ended().has_value());
  EXPECT_FALSE(other_type->ended().has_value());

  std::optional<grpc::Status> end = slow->ended();
  ASSERT_TRUE(end.has_value()) << "the slow subscriber was not ended";
  EXPECT_EQ(end->error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(end->error_message().find("too slow"), std::string::npos) << end->error_message();
  EXPECT_EQ(hub.subscribers(), 2u) << "the ended subscriber is still in the hub";
  EXPECT_EQ(hub.dropped_subscribers(), 1u);

  // It gets nothing more, and a reader is not kept waiting for it.
  hub.publish(received("t.Status", 1, 99));
  auto start = std::chrono::steady_clock::now();
  while (auto message = slow->next(10s)) {
    EXPECT_NE(message->receive_time(), 99) << "a message published after the end was delivered";
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5s) << "next() waited on an ended subscription";
  EXPECT_EQ(slow->ended()->error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << "the reason was replaced";
  EXPECT_EQ(hub.dropped_subscribers(), 1u);
}

TEST(SubscriberHubTest, EndedSubscriberLeavesTheHubByTheNextPublish) {
  SubscriberHub hub(2);
  auto slow = hub.subscribe({{"t.Status"}, std::nullopt});
  for (int i = 0; i < 3; ++i) hub.publish(received("t.Status", 1, i));
  ASSERT_TRUE(slow->ended().has_value());
  hub.publish(received("t.Ctd", 1));  // a message it does not even want
  EXPECT_EQ(hub.subscribers(), 0u);
  EXPECT_EQ(hub.dropped_subscribers(), 1u);
}

TEST(SubscriberHubTest, PublishNeverBlocksOnSubscribersThatDoNotRead) {
  SubscriberHub hub(16);
  std::vector<std::shared_ptr<Subscription>> idle;
  for (int i = 0; i < 50; ++i) idle.push_back(hub.subscribe({}));
  // One reader sits in next() on a type that never comes.
  auto waiting = hub.subscribe({{"t.Never"}, std::nullopt});
  auto waiter = std::async(std::launch::async, [&] { return waiting->next(20s); });
  auto publisher = std::async(std::launch::async, [&] {
    for (int i = 0; i < 100000; ++i) hub.publish(received("t.Status", 1, i));
  });
  ASSERT_EQ(publisher.wait_for(60s), std::future_status::ready) << "publish() blocked";
  for (const auto& s : idle) {
    ASSERT_TRUE(s->ended().has_value());
    EXPECT_EQ(s->ended()->error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  }
  EXPECT_EQ(hub.subscribers(), 1u);
  EXPECT_EQ(hub.dropped_subscribers(), 50u);
  hub.close();  // wakes the waiter
  ASSERT_EQ(waiter.wait_for(30s), std::future_status::ready) << "close() did not wake a waiting reader";
  EXPECT_FALSE(waiter.get().has_value());
}

TEST(SubscriberHubTest, CloseEndsEveryoneWithUnavailableAndLaterSubscriptionsAreEndedAtOnce) {
  SubscriberHub hub(8);
  auto one = hub.subscribe({});
  auto two = hub.subscribe({{"t.Status"}, 3});
  hub.publish(received("t.Status", 3, 1));
  hub.close();
  EXPECT_EQ(hub.subscribers(), 0u);
  for (const auto& s : {one, two}) {
    ASSERT_TRUE(s->ended().has_value());
    EXPECT_EQ(s->ended()->error_code(), grpc::StatusCode::UNAVAILABLE);
  }
  // What was buffered before the end is still read, then the stream ends.
  auto first = one->next(0ms);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->receive_time(), 1);
  EXPECT_FALSE(one->next(0ms).has_value());

  auto late = hub.subscribe({});
  ASSERT_TRUE(late->ended().has_value()) << "subscribe() after close() returned a live subscription";
  EXPECT_EQ(late->ended()->error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(hub.subscribers(), 0u);
  hub.publish(received("t.Status", 3, 2));
  auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(late->next(10s).has_value());
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5s) << "next() waited on an ended subscription";
  std::vector<double> two_got;
  while (auto message = two->next(0ms)) two_got.push_back(message->receive_time());
  EXPECT_EQ(two_got, std::vector<double>{1}) << "delivered after close";
  // Closing ends; it does not count as dropping slow subscribers.
  EXPECT_EQ(hub.dropped_subscribers(), 0u);
}

TEST(SubscriberHubTest, UnsubscribeRemoves) {
  SubscriberHub hub(8);
  auto stays = hub.subscribe({});
  auto leaves = hub.subscribe({});
  EXPECT_EQ(hub.subscribers(), 2u);
  hub.unsubscribe(leaves);
  EXPECT_EQ(hub.subscribers(), 1u);
  hub.publish(received("t.Status", 1, 7));
  EXPECT_FALSE(leaves->next(0ms).has_value()) << "delivered after unsubscribe";
  auto got = stays->next(0ms);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->receive_time(), 7);
  hub.unsubscribe(leaves);  // twice: harmless
  EXPECT_EQ(hub.subscribers(), 1u);
  EXPECT_EQ(hub.dropped_subscribers(), 0u) << "unsubscribing is not being dropped";
}

TEST(SubscriberHubTest, EndKeepsTheFirstReason) {
  Subscription subscription({}, 4);
  subscription.offer(received("t.A", 1, 1));
  subscription.end(grpc::Status(grpc::StatusCode::CANCELLED, "client went away"));
  subscription.end(grpc::Status(grpc::StatusCode::UNAVAILABLE, "stopping"));
  subscription.offer(received("t.A", 1, 2));  // after the end: ignored
  ASSERT_TRUE(subscription.ended().has_value());
  EXPECT_EQ(subscription.ended()->error_code(), grpc::StatusCode::CANCELLED);
  auto first = subscription.next(0ms);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->receive_time(), 1);
  EXPECT_FALSE(subscription.next(0ms).has_value());
}

}  // namespace
}  // namespace acomms::service
