// EventLogRetention (daemon/queue/event_log_retention.h) on the simulated
// clock over a real store: old events go in steps of bounded size, what
// must stay stays (queued messages' events, received events inside the
// duplicate window, the sequence counter), and a replay asking for pruned
// history is refused naming the first seq still held.

#include "queue/event_log_retention.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/scheduler.h"
#include "queue/event_log_reader.h"
#include "queue/sqlite_journal.h"
#include "store/group_commit_writer.h"
#include "store/store.h"
#include "store_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr double kDay = 86400;
constexpr double kNow = 1'700'000'000;  // the simulated clock's start

QueueEvent event_at(double time, QueueEventKind kind, int64_t message_id = 0, int64_t seq = 0) {
  QueueEvent e;
  e.kind = kind;
  e.time = time;
  e.type = "a.A";
  e.message_id = message_id;
  e.src = 2;
  e.dest = 1;
  if (kind == QueueEventKind::kReceived) e.encoded = "bytes" + std::to_string(seq);
  e.seq = seq;
  return e;
}

class EventLogRetentionTest : public acomms::testing::StoreFixture {
 protected:
  void SetUp() override {
    open();
  }
  void TearDown() override {
    retention_.reset();
    close();
  }
  void open() {
    open_store();
    reader_ = std::make_unique<EventLogReader>(store_->db().path());
  }
  void close() {
    reader_.reset();
    close_store();
  }
  void start(RetentionPolicy policy, double duplicate_window_s = 300) {
    retention_ = std::make_unique<EventLogRetention>(*writer_, scheduler_, policy,
                                                     [duplicate_window_s](double now) { return now - duplicate_window_s; });
    retention_->start();
  }
  // One step's worth of simulated time, then waits for the step's commit.
  void run_step() {
    scheduler_.run_for(EventLogRetention::kBacklogInterval);
    writer_->flush();
  }
  int64_t count(const std::string& where) {
    return writer_
        ->submit([where](store::Database& db) {
          store::Statement s = db.prepare("SELECT COUNT(*) FROM event_log WHERE " + where);
          s.step();
          return s.column_int64(0);
        })
        .get();
  }

  core::SimulatedScheduler scheduler_{core::Clock::time_point(std::chrono::seconds(static_cast<int64_t>(kNow)))};
  std::unique_ptr<EventLogReader> reader_;
  std::unique_ptr<EventLogRetention> retention_;
};

TEST_F(EventLogRetentionTest, OldEventsArePrunedInStepsOfBoundedSizeAndRecentOnesStay) {
  for (int i = 0; i < 1000; ++i) journal_->record(event_at(kNow - 100 * kDay + i, QueueEventKind::kSent, 1000 + i));
  for (int i = 0; i < 50; ++i) journal_->record(event_at(kNow - 10 * kDay + i, QueueEventKind::kSent, 5000 + i));
  journal_->flush();
  RetentionPolicy policy;
  policy.max_age_s = 90 * kDay;
  policy.max_bytes = 0;
  policy.rows_per_step = 100;
  start(policy);
  for (int step = 1; step <= 10; ++step) {
    run_step();
    EXPECT_EQ(retention_->pruned(), static_cast<uint64_t>(100 * step)) << "after step " << step;
  }
  run_step();
  EXPECT_EQ(retention_->pruned(), 1000u);
  EXPECT_EQ(count("1"), 50);
  EXPECT_EQ(count("time < " + std::to_string(kNow - 90 * kDay)), 0);
}

TEST_F(EventLogRetentionTest, QueuedMessagesAndTheirEventsAreNeverPruned) {
  JournalMessage message;
  message.type = "a.A";
  message.payload = "p";
  message.dest = 2;
  message.submitted_at = kNow - 200 * kDay;  // its "queued" event is this old
  const int64_t id = journal_->append(message);
  journal_->record(event_at(kNow - 150 * kDay, QueueEventKind::kSent, id));
  journal_->record(event_at(kNow - 150 * kDay, QueueEventKind::kSent, id + 1));  // a message long gone
  journal_->flush();
  RetentionPolicy policy;
  policy.max_age_s = 90 * kDay;
  policy.max_bytes = 0;
  start(policy);
  run_step();
  EXPECT_EQ(retention_->pruned(), 1u);
  EXPECT_EQ(count("message_id = " + std::to_string(id)), 2);
  ASSERT_EQ(journal_->load().size(), 1u);
  EXPECT_EQ(journal_->load().front().id, id);
}

TEST_F(EventLogRetentionTest, ReceivedEventsInsideTheDuplicateWindowStayPastTheAgeBound) {
  journal_->record(event_at(kNow - 200, QueueEventKind::kReceived, 0, 1));
  journal_->record(event_at(kNow - 200, QueueEventKind::kSent, 7));
  journal_->record(event_at(kNow - 400, QueueEventKind::kReceived, 0, 2));
  journal_->flush();
  RetentionPolicy policy;
  policy.max_age_s = 60;  // shorter than the 300 s duplicate window
  policy.max_bytes = 0;
  start(policy, 300);
  run_step();
  EXPECT_EQ(retention_->pruned(), 2u);
  EXPECT_EQ(count("seq = 1"), 1);
  EXPECT_EQ(journal_->received_since(kNow - 300).size(), 1u);
}

TEST_F(EventLogRetentionTest, PrunedHistoryIsOutOfRangeAndItsNumbersAreNeverHandedOutAgain) {
  for (int64_t seq = 1; seq <= 5; ++seq) {
    journal_->record(event_at(kNow - 100 * kDay + static_cast<double>(seq), QueueEventKind::kReceived, 0, seq));
  }
  journal_->flush();
  RetentionPolicy policy;
  policy.max_age_s = 90 * kDay;
  policy.max_bytes = 0;
  start(policy);
  run_step();
  EXPECT_EQ(retention_->pruned(), 5u);
  ReceivedRange range = reader_->received_range();
  EXPECT_EQ(range.last, 5);
  EXPECT_EQ(range.first, 6);  // none held: the next one
  EXPECT_FALSE(range.replayable_after(0));
  EXPECT_FALSE(range.replayable_after(4));
  EXPECT_TRUE(range.replayable_after(5));  // a client that had everything
  // A restart continues after 5, though no event with 5 is left.
  retention_.reset();
  close();
  open();
  EXPECT_EQ(journal_->last_received_seq(), 5);
  journal_->record(event_at(kNow, QueueEventKind::kReceived, 0, 6));
  journal_->flush();
  range = reader_->received_range();
  EXPECT_EQ(range.first, 6);
  EXPECT_FALSE(range.replayable_after(3));
  EXPECT_TRUE(range.replayable_after(5));
}

TEST_F(EventLogRetentionTest, OverTheSizeBoundTheOldestGoWhateverTheirAge) {
  const std::string detail(2000, 'x');
  for (int i = 0; i < 2000; ++i) {
    QueueEvent e = event_at(kNow - 1000 + i * 0.1, QueueEventKind::kSent, 100 + i);
    e.detail = detail;
    journal_->record(e);
  }
  journal_->flush();
  RetentionPolicy policy;
  policy.max_age_s = 0;
  policy.max_bytes = 1 << 20;  // about a quarter of what is there
  policy.rows_per_step = 200;
  start(policy, 0);
  for (int step = 0; step < 20; ++step) run_step();
  const int64_t left = count("1");
  EXPECT_LT(left, 700);
  EXPECT_GT(left, 200);  // stopped once under the bound, not emptied
  // What is left is the newest.
  EXPECT_EQ(count("message_id >= " + std::to_string(100 + 2000 - left)), left);
}

}  // namespace
}  // namespace acomms::queue
