// The node's choice of link (link/link_choice.h) on the simulated clock:
// the order of a route, the fallback after a link has not reached the
// destination for fallback_after_s, the way back when it is heard again,
// cost against priority, and that exactly one link carries a routed
// message at any time.

#include "link/link_choice.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/clock.h"

namespace acomms::link {
namespace {

using namespace std::chrono_literals;

constexpr int kAcoustic = 0;
constexpr int kIridium = 1;
constexpr int32_t kShore = 7;

class LinkChoiceTest : public ::testing::Test {
 protected:
  LinkChoice make(const std::string& queue_text, double iridium_cost = 0) {
    std::vector<v1::LinkConfig> links(2);
    links[0].set_name("acoustic");
    links[1].set_name("iridium");
    links[1].set_cost(iridium_cost);
    v1::QueueConfig queue;
    EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(queue_text, &queue)) << queue_text;
    return LinkChoice::from_config(links, queue, now());
  }
  double now() const { return clock_.now_seconds(); }
  void wait(std::chrono::seconds s) { clock_.advance(s); }

  core::SimulatedClock clock_{core::Clock::time_point(std::chrono::seconds(1'750'000'000))};
};

constexpr const char* kStatusRoute =
    R"(type { type: "x.Status" route { dest: 7 link: "acoustic" link: "iridium" fallback_after_s: 600 } })";

TEST_F(LinkChoiceTest, FirstLinkCarriesWhileItReachesTheDestination) {
  LinkChoice choice = make(kStatusRoute);
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kAcoustic);
  EXPECT_TRUE(choice.may_carry(kAcoustic, "x.Status", kShore, 0.1, now()));
  EXPECT_FALSE(choice.may_carry(kIridium, "x.Status", kShore, 0.1, now()));
  for (int i = 0; i < 10; ++i) {
    wait(300s);
    choice.reached(kAcoustic, kShore, now());
    EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kAcoustic) << "after " << (i + 1) * 300 << " s";
  }
}

TEST_F(LinkChoiceTest, NextLinkTakesOverAfterTheSilenceAndTheFirstComesBackWhenHeard) {
  LinkChoice choice = make(kStatusRoute);
  wait(600s);  // never heard: counted from the start
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kAcoustic) << "the silence is not yet longer than 600 s";
  wait(1s);
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kIridium);
  EXPECT_TRUE(choice.may_carry(kIridium, "x.Status", kShore, 0.1, now()));
  EXPECT_FALSE(choice.may_carry(kAcoustic, "x.Status", kShore, 0.1, now()));
  // Another node heard on acoustic says nothing about the shore.
  choice.reached(kAcoustic, 3, now());
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kIridium);
  wait(30s);
  choice.reached(kAcoustic, kShore, now());
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kAcoustic);
  wait(601s);
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kIridium);
}

TEST_F(LinkChoiceTest, ExactlyOneLinkMayCarryARoutedMessageAtAnyTime) {
  LinkChoice choice = make(kStatusRoute);
  for (int minute = 0; minute < 60; ++minute) {
    if (minute % 25 == 0) choice.reached(kAcoustic, kShore, now());
    int carriers = choice.may_carry(kAcoustic, "x.Status", kShore, 1, now()) +
                   choice.may_carry(kIridium, "x.Status", kShore, 1, now());
    EXPECT_EQ(carriers, 1) << "minute " << minute;
    wait(60s);
  }
}

TEST_F(LinkChoiceTest, DisabledOrFailedLinkIsPassedOverAtOnce) {
  LinkChoice choice = make(kStatusRoute);
  choice.reached(kAcoustic, kShore, now());
  choice.set_driver_up(kAcoustic, false);
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kIridium);
  EXPECT_FALSE(choice.may_carry(kAcoustic, "x.Status", kShore, 1, now()));
  choice.set_driver_up(kAcoustic, true);
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kAcoustic);
  choice.set_enabled(kIridium, false);
  wait(3600s);
  // Acoustic unheard for an hour, iridium disabled (underwater): the last
  // usable link keeps trying.
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kAcoustic);
  choice.set_enabled(kAcoustic, false);
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), -1);
  EXPECT_FALSE(choice.may_carry(kAcoustic, "x.Status", kShore, 1, now()));
  EXPECT_FALSE(choice.may_carry(kIridium, "x.Status", kShore, 1, now()));
}

TEST_F(LinkChoiceTest, PriorityMustBeatTheLinksCost) {
  LinkChoice choice = make(kStatusRoute, /*iridium_cost=*/0.5);
  wait(601s);
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kIridium);
  EXPECT_FALSE(choice.may_carry(kIridium, "x.Status", kShore, 0.4, now()));
  EXPECT_FALSE(choice.may_carry(kIridium, "x.Status", kShore, 0.5, now())) << "equal is not beating it";
  EXPECT_TRUE(choice.may_carry(kIridium, "x.Status", kShore, 0.51, now()));
  // The cost bars unrouted types too; a link without cost bars nothing.
  EXPECT_FALSE(choice.may_carry(kIridium, "x.Other", kShore, 0.2, now()));
  EXPECT_TRUE(choice.may_carry(kAcoustic, "x.Other", kShore, 0.0, now()));
}

TEST_F(LinkChoiceTest, UnroutedMessageMayGoOnAnyUsableLink) {
  LinkChoice choice = make(kStatusRoute);
  EXPECT_EQ(choice.carrier("x.Other", kShore, now()), -1);
  EXPECT_EQ(choice.carrier("x.Status", 3, now()), -1) << "the route is for destination 7 only";
  EXPECT_TRUE(choice.may_carry(kAcoustic, "x.Status", 3, 0, now()));
  EXPECT_TRUE(choice.may_carry(kIridium, "x.Status", 3, 0, now()));
  choice.set_enabled(kIridium, false);
  EXPECT_FALSE(choice.may_carry(kIridium, "x.Other", 3, 0, now()));
}

TEST_F(LinkChoiceTest, TypesOwnRouteWinsOverTheQueueWideOne) {
  LinkChoice choice = make(
      R"(route { link: "iridium" } )"
      R"(type { type: "x.Status" route { dest: 7 link: "acoustic" link: "iridium" fallback_after_s: 600 } })");
  EXPECT_EQ(choice.carrier("x.Status", kShore, now()), kAcoustic);
  EXPECT_EQ(choice.carrier("x.Status", 3, now()), kIridium) << "no route of its own for 3: the queue-wide one";
  EXPECT_EQ(choice.carrier("x.Other", kShore, now()), kIridium);
}

TEST_F(LinkChoiceTest, BroadcastIsReachedByAnyReceptionOnTheLink) {
  LinkChoice choice = make(R"(route { dest: 0 link: "acoustic" link: "iridium" fallback_after_s: 60 })");
  wait(61s);
  EXPECT_EQ(choice.carrier("x.Status", 0, now()), kIridium);
  choice.reached(kAcoustic, 12, now());
  EXPECT_EQ(choice.carrier("x.Status", 0, now()), kAcoustic);
}

TEST_F(LinkChoiceTest, RouteNamingNoSuchLinkIsRefused) {
  EXPECT_THROW(make(R"(route { link: "satellite" })"), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::link
