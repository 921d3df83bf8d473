// What a gateway keeps of routing across a restart (route/route_journal.h):
// the origin's end-to-end notes (migrations/0014) and its learned routes
// (migrations/0015), on a real SQLite store closed and reopened between
// two lives, with the clock's seconds given by the test.

#include "route/route_journal.h"

#include <gtest/gtest.h>

#include "store_fixture.h"

namespace acomms::route {
namespace {

constexpr double kT0 = 1'748'772'000;

class RouteJournalTest : public acomms::testing::StoreFixture {
 protected:
  void SetUp() override { reopen(); }
  void TearDown() override {
    routes_.reset();
    close_store();
  }
  // A restart: everything written so far is committed, the store closed
  // and opened again, and a new RouteJournal made on it.
  void reopen() {
    if (writer_) writer_->flush();
    routes_.reset();
    close_store();
    open_store();
    routes_ = std::make_unique<RouteJournal>(*writer_);
  }
  static RoutedSend send(int64_t id, double sent_at, double forget_after) {
    return {id, "net.Command", 3, 2, sent_at, false, forget_after};
  }
  // learned_max_age_s 1800 s (the default).
  static RouteTable table() { return RouteTable(v1::RoutingConfig(), {"sat", "acoustic"}, 1); }

  std::unique_ptr<RouteJournal> routes_;
};

TEST_F(RouteJournalTest, NotesAwaitingTheirEndToEndAckSurviveARestartWithTheirHopAck) {
  EndToEndAcks acks;
  acks.attach(routes_.get(), kT0);
  acks.sent(send(70000, kT0, kT0 + 4000));  // sequence 4464
  acks.sent(send(12, kT0 + 1, kT0 + 4000));
  ASSERT_TRUE(acks.hop_acked(70000));
  reopen();

  EndToEndAcks after;
  after.attach(routes_.get(), kT0 + 600);
  const RoutedSend* noted = after.find(4464);
  ASSERT_NE(noted, nullptr);
  EXPECT_EQ(noted->message_id, 70000);
  EXPECT_EQ(noted->type, "net.Command");
  EXPECT_EQ(noted->dest, 3);
  EXPECT_EQ(noted->next_hop, 2);
  EXPECT_DOUBLE_EQ(noted->sent_at, kT0);
  EXPECT_DOUBLE_EQ(noted->forget_after, kT0 + 4000);
  EXPECT_TRUE(noted->hop_acked);
  ASSERT_NE(after.find(12), nullptr);
  EXPECT_FALSE(after.find(12)->hop_acked);

  // A receipt takes its note, in the store too.
  ASSERT_TRUE(after.take(4464));
  reopen();
  EndToEndAcks third;
  third.attach(routes_.get(), kT0 + 700);
  EXPECT_EQ(third.find(4464), nullptr);
  EXPECT_NE(third.find(12), nullptr);
}

TEST_F(RouteJournalTest, NotesArePrunedPastTheirTimeAndBoundedInNumber) {
  EndToEndAcks acks(2);
  acks.attach(routes_.get(), kT0);
  acks.sent(send(1, kT0, kT0 + 100));
  acks.sent(send(2, kT0 + 10, kT0 + 5000));
  acks.sent(send(3, kT0 + 20, kT0 + 5000));  // full: 1, the oldest sent, goes
  EXPECT_EQ(acks.find(1), nullptr);
  reopen();
  {
    EndToEndAcks after(2);
    after.attach(routes_.get(), kT0 + 30);
    EXPECT_EQ(after.list().size(), 2u);
    EXPECT_EQ(after.find(1), nullptr);  // its row went with it
    // A note past its forget_after goes at the next send, from the store too.
    after.sent(send(4, kT0 + 50, kT0 + 60));
    after.sent(send(5, kT0 + 100, kT0 + 5000));
    EXPECT_EQ(after.find(4), nullptr);
  }
  reopen();
  {
    // 2 went for the bound, 4 for its time: the store has 3 and 5.
    EndToEndAcks kept(10);
    kept.attach(routes_.get(), kT0 + 4999);
    std::vector<RoutedSend> listed = kept.list();
    ASSERT_EQ(listed.size(), 2u);
    EXPECT_EQ(listed[0].message_id, 3);
    EXPECT_EQ(listed[1].message_id, 5);
  }
  reopen();
  // Notes past their time when the store is read are not read back.
  EndToEndAcks gone(10);
  gone.attach(routes_.get(), kT0 + 5001);
  EXPECT_TRUE(gone.list().empty());
}

TEST_F(RouteJournalTest, LearnedRoutesSurviveARestartAndAgeWhileTheNodeWasDown) {
  {
    RouteTable routes = table();
    routes.attach(routes_.get(), kT0);
    routes.heard(3, "acoustic", kT0);
    routes.heard_through(9, 3, "acoustic", kT0 + 5);
  }
  reopen();
  RouteTable routes = table();
  // Back 100 s after the last confirmation: both routes still used.
  routes.attach(routes_.get(), kT0 + 100);
  std::vector<RouteEntry> listed = routes.list(kT0 + 100);
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(listed[0].dest_min, 3);
  EXPECT_EQ(listed[0].next, (NextHop{3, "acoustic", RouteSource::kLearnedDirect}));
  EXPECT_DOUBLE_EQ(*listed[0].last_confirmed, kT0);
  EXPECT_EQ(listed[1].dest_min, 9);
  EXPECT_EQ(listed[1].next, (NextHop{3, "acoustic", RouteSource::kLearnedRelay}));
  EXPECT_DOUBLE_EQ(*listed[1].last_confirmed, kT0 + 5);
  EXPECT_EQ(routes.next_hop(9, kT0 + 100), (NextHop{3, "acoustic", RouteSource::kLearnedRelay}));
  // The time down counts: 1800 s after its confirmation a route is stale.
  EXPECT_FALSE(routes.next_hop(3, kT0 + 1801));
  EXPECT_TRUE(routes.list(kT0 + 1801)[0].stale);
}

TEST_F(RouteJournalTest, AStoredRouteIsNeverYoungerThanTheRealOne) {
  constexpr double kEvery = RouteTable::kPersistEveryS;
  {
    RouteTable routes = table();
    routes.attach(routes_.get(), kT0);
    routes.heard(3, "acoustic", kT0);               // new: written
    routes.heard(3, "acoustic", kT0 + 10);          // confirmed again: not written yet
    routes.heard(3, "acoustic", kT0 + kEvery + 1);  // written
    routes.heard(3, "acoustic", kT0 + kEvery + 5);  // not written
    routes.heard(4, "acoustic", kT0);
    routes.heard(4, "sat", kT0 + 5);  // changed: written at once
  }
  reopen();
  RouteTable routes = table();
  routes.attach(routes_.get(), kT0 + 100);
  std::vector<RouteEntry> listed = routes.list(kT0 + 100);
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_DOUBLE_EQ(*listed[0].last_confirmed, kT0 + kEvery + 1);  // really kT0 + kEvery + 5: looks 4 s older
  EXPECT_EQ(listed[1].next.link, "sat");
  EXPECT_DOUBLE_EQ(*listed[1].last_confirmed, kT0 + 5);
}

TEST_F(RouteJournalTest, AStoredRouteThatNoLongerFitsTheNodeIsDroppedAndAClockGoneBackIsClamped) {
  {
    RouteTable routes(v1::RoutingConfig(), {"sat", "acoustic", "udp"}, 1);
    routes.attach(routes_.get(), kT0);
    routes.heard(3, "udp", kT0);          // a link this node will no longer have
    routes.heard(5, "acoustic", kT0 + 500);  // later than the next start's clock
  }
  reopen();
  RouteTable routes = table();
  routes.attach(routes_.get(), kT0 + 100);
  std::vector<RouteEntry> listed = routes.list(kT0 + 100);
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].dest_min, 5);
  EXPECT_DOUBLE_EQ(*listed[0].last_confirmed, kT0 + 100);
}

}  // namespace
}  // namespace acomms::route
