// ReceivedMessageRouter (daemon/node/received_message_router.h): telemetry's
// types go to telemetry and never to subscribers; every other type is
// published only once its event is stored, with what Subscribe streams
// (type, payload, seq, source, link figures), and still published when the
// store reports it may not be.

#include "node/received_message_router.h"

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "telemetry/wire_message.h"

namespace acomms::node {
namespace {

// A received message carrying `body` (any protobuf message will do: the
// router only reads its type name, seq and source).
queue::ReceivedMessage received(const std::string& type, int64_t seq) {
  queue::ReceivedMessage message;
  message.type = type;
  auto body = std::make_unique<v1::ModemTransmission>();
  body->set_src(9);
  message.message = std::move(body);
  message.seq = seq;
  message.src = 3;
  message.dest = 1;
  message.time = 1000.5;
  return message;
}

v1::ModemTransmission transmission_from(int32_t src) {
  v1::ModemTransmission from;
  from.set_src(src);
  return from;
}

struct Recorder {
  std::vector<std::string> to_telemetry;
  std::vector<v1::ReceivedMessage> published;
  // The commit callbacks the router is waiting on, in order.
  std::vector<queue::MessageJournal::Committed> waiting;
  // Work handed to the core for later, not yet run.
  std::vector<std::function<void()>> later;
  // What happened, in order: "telemetry TYPE" or "store? SEQ".
  std::vector<std::string> order;

  ReceivedMessageRouter router() {
    return ReceivedMessageRouter(
        [this](const queue::ReceivedMessage& m) {
          to_telemetry.push_back(m.type);
          order.push_back("telemetry " + m.type);
        },
        [this](queue::MessageJournal::Committed committed) {
          waiting.push_back(std::move(committed));
          order.push_back("store? " + std::to_string(waiting.size()));
        },
        [this](const v1::ReceivedMessage& m) { published.push_back(m); },
        [this](std::function<void()> work) { later.push_back(std::move(work)); });
  }
  void run_later() {
    for (auto& work : later) work();
    later.clear();
  }
};

TEST(ReceivedMessageRouter, TelemetryTypesGoToTelemetryAndNeverToSubscribers) {
  Recorder seen;
  ReceivedMessageRouter router = seen.router();
  router.route(received(std::string(telemetry::kFullType), 1), transmission_from(3));
  router.route(received(std::string(telemetry::kDeltaType), 2), transmission_from(3));
  EXPECT_TRUE(seen.to_telemetry.empty()) << "handed on at once, not after the core's current work";
  seen.run_later();
  EXPECT_EQ(seen.to_telemetry,
            (std::vector<std::string>{std::string(telemetry::kFullType), std::string(telemetry::kDeltaType)}));
  EXPECT_TRUE(seen.waiting.empty());
  EXPECT_TRUE(seen.published.empty());
}

TEST(ReceivedMessageRouter, OtherTypesArePublishedOnlyOnceTheirEventIsStored) {
  Recorder seen;
  ReceivedMessageRouter router = seen.router();
  router.route(received("gv.NavigationReport", 41), transmission_from(3));
  router.route(received("gv.Status", 42), transmission_from(3));
  ASSERT_EQ(seen.waiting.size(), 2u);
  EXPECT_TRUE(seen.published.empty()) << "published before its event was stored";
  EXPECT_TRUE(seen.to_telemetry.empty());

  seen.waiting[0](nullptr);
  ASSERT_EQ(seen.published.size(), 1u);
  const v1::ReceivedMessage& first = seen.published[0];
  EXPECT_EQ(first.type(), "gv.NavigationReport");
  EXPECT_EQ(first.seq(), 41);
  EXPECT_EQ(first.src(), 3);
  EXPECT_EQ(first.dest(), 1);
  EXPECT_DOUBLE_EQ(first.receive_time(), 1000.5);
  v1::ModemTransmission body;
  ASSERT_TRUE(body.ParseFromString(first.payload()));
  EXPECT_EQ(body.src(), 9);

  seen.waiting[1](nullptr);
  ASSERT_EQ(seen.published.size(), 2u);
  EXPECT_EQ(seen.published[1].seq(), 42);
}

// Telemetry numbers the Positions it reconstructs after the messages of the
// same transmission (which hold lower numbers): their "publish once stored"
// requests must reach the store first, or a live subscriber would be sent a
// Position before them and then skip them as not newer.
TEST(ReceivedMessageRouter, TelemetryIsHandedOnAfterTheTransmissionsOtherMessagesAskedToBeStored) {
  Recorder seen;
  ReceivedMessageRouter router = seen.router();
  // One transmission: a telemetry delta (seq 5), then a command (seq 6).
  router.route(received(std::string(telemetry::kDeltaType), 5), transmission_from(3));
  router.route(received("gv.Command", 6), transmission_from(3));
  seen.run_later();  // the core's next work
  EXPECT_EQ(seen.order, (std::vector<std::string>{"store? 1", "telemetry " + std::string(telemetry::kDeltaType)}));
}

// Heard is heard: the sender forgets it once ACKed, so a subscriber still
// gets it (the daemon logs that it may not be stored).
TEST(ReceivedMessageRouter, AMessageWhoseEventMayNotBeStoredIsStillPublished) {
  Recorder seen;
  ReceivedMessageRouter router = seen.router();
  router.route(received("gv.Status", 7), transmission_from(3));
  ASSERT_EQ(seen.waiting.size(), 1u);
  seen.waiting[0](std::make_exception_ptr(std::runtime_error("disk full")));
  ASSERT_EQ(seen.published.size(), 1u);
  EXPECT_EQ(seen.published[0].seq(), 7);
}

}  // namespace
}  // namespace acomms::node
