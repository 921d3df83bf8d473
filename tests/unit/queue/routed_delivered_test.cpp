// The identities of routed messages delivered at this node, kept by the
// SQLite journal with their received events (migrations/0013): what a
// destination remembers across a SIGKILL so that a copy arriving after it is
// not delivered twice (route/delivered_identities.h).

#include <gtest/gtest.h>

#include "queue/sqlite_journal.h"
#include "store_fixture.h"

namespace acomms::queue {
namespace {

class RoutedDeliveredTest : public acomms::testing::StoreFixture {
 protected:
  void SetUp() override { open_store(); }
  static QueueEvent received(int32_t origin, int32_t seq, double forget_after) {
    QueueEvent e;
    e.kind = QueueEventKind::kReceived;
    e.time = 1000;
    e.type = "test.Command";
    e.encoded = "c";
    e.routed = RoutedIdentity{origin, seq, forget_after};
    return e;
  }
};

TEST_F(RoutedDeliveredTest, IdentitiesSurviveAReopenUntilTheirTimeAndAWrappedSequenceReplacesItsRow) {
  journal_->record(received(1, 65535, 2000));
  journal_->record(received(1, 0, 3000));  // the origin's sequence wrapped
  journal_->record(received(4, 7, 1500));
  QueueEvent plain = received(0, 0, 0);  // not routed: no row
  plain.routed.reset();
  journal_->record(plain);
  journal_->flush();
  close_store();
  open_store();
  std::vector<RoutedIdentity> kept = journal_->routed_since(1000);
  ASSERT_EQ(kept.size(), 3u);
  // Oldest due first.
  EXPECT_EQ(kept[0].origin, 4);
  EXPECT_EQ(kept[0].seq, 7);
  EXPECT_EQ(kept[1].seq, 65535);
  EXPECT_EQ(kept[2].seq, 0);
  EXPECT_DOUBLE_EQ(kept[2].forget_after, 3000);
  // Past their time they are forgotten, and stay so.
  EXPECT_EQ(journal_->routed_since(1800).size(), 2u);
  EXPECT_EQ(journal_->routed_since(1000).size(), 2u);
  // The same identity again (after 2^16 more messages): one row, the new time.
  journal_->record(received(1, 0, 5000));
  journal_->flush();
  kept = journal_->routed_since(4000);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_DOUBLE_EQ(kept[0].forget_after, 5000);
}

}  // namespace
}  // namespace acomms::queue
