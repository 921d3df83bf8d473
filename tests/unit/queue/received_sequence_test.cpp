// Received sequence numbers in the store (migrations/0005): the journal
// makes each durable with its event, the counter survives a reopen, and the
// reader replays "everything after N" in seq order with Subscribe's filters.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "queue/event_log_reader.h"
#include "queue/sqlite_journal.h"
#include "store/group_commit_writer.h"
#include "store/store.h"
#include "store_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;

constexpr double kT = 1'700'000'000;

QueueEvent received(int64_t seq, const std::string& type, int32_t src, std::string encoded) {
  QueueEvent e;
  e.kind = QueueEventKind::kReceived;
  e.time = kT + static_cast<double>(seq);
  e.type = type;
  e.src = src;
  e.dest = 1;
  e.encoded = std::move(encoded);
  e.seq = seq;
  return e;
}

class ReceivedSequenceTest : public acomms::testing::StoreFixture {
 protected:
  void SetUp() override {
    open();
  }
  void TearDown() override {
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
  static std::vector<int64_t> seqs(const std::vector<StoredReceived>& page) {
    std::vector<int64_t> out;
    for (const StoredReceived& r : page) out.push_back(r.seq);
    return out;
  }

  std::unique_ptr<EventLogReader> reader_;
};

TEST_F(ReceivedSequenceTest, ANewStoreHasHandedOutNoNumber) {
  EXPECT_EQ(journal_->last_received_seq(), 0);
  ReceivedRange range = reader_->received_range();
  EXPECT_EQ(range.last, 0);
  EXPECT_EQ(range.first, 1);
  EXPECT_TRUE(reader_->received_after(0, {}, std::nullopt, 10).empty());
}

TEST_F(ReceivedSequenceTest, TheLastNumberSurvivesReopeningTheStore) {
  for (int64_t seq = 1; seq <= 3; ++seq) journal_->record(received(seq, "a.A", 2, "x" + std::to_string(seq)));
  journal_->flush();
  close();
  open();
  EXPECT_EQ(journal_->last_received_seq(), 3);
  EXPECT_EQ(reader_->received_range().first, 1);
  EXPECT_EQ(reader_->received_range().last, 3);
}

TEST_F(ReceivedSequenceTest, ReplayIsInSeqOrderAfterTheCursorWithItsBytes) {
  for (int64_t seq = 1; seq <= 5; ++seq) journal_->record(received(seq, "a.A", 2, "m" + std::to_string(seq)));
  journal_->flush();
  std::vector<StoredReceived> page = reader_->received_after(2, {}, std::nullopt, 10);
  EXPECT_EQ(seqs(page), (std::vector<int64_t>{3, 4, 5}));
  ASSERT_EQ(page.size(), 3u);
  EXPECT_EQ(page[0].encoded, "m3");
  EXPECT_EQ(page[0].type, "a.A");
  EXPECT_EQ(page[0].src, 2);
  EXPECT_EQ(page[0].dest, 1);
  EXPECT_DOUBLE_EQ(page[0].time, kT + 3);
  // `limit` pages: the next page starts after the last seq read.
  EXPECT_EQ(seqs(reader_->received_after(0, {}, std::nullopt, 2)), (std::vector<int64_t>{1, 2}));
}

TEST_F(ReceivedSequenceTest, ReplayAppliesTheTypeAndSourceFilters) {
  journal_->record(received(1, "a.A", 2, "1"));
  journal_->record(received(2, "b.B", 2, "2"));
  journal_->record(received(3, "a.A", 3, "3"));
  journal_->record(received(4, "b.B", 3, "4"));
  // Events of other kinds carry no seq and are never replayed.
  QueueEvent sent;
  sent.kind = QueueEventKind::kSent;
  sent.time = kT;
  sent.type = "a.A";
  sent.message_id = 9;
  journal_->record(sent);
  journal_->flush();
  EXPECT_EQ(seqs(reader_->received_after(0, {"a.A"}, std::nullopt, 10)), (std::vector<int64_t>{1, 3}));
  EXPECT_EQ(seqs(reader_->received_after(0, {}, 3, 10)), (std::vector<int64_t>{3, 4}));
  EXPECT_EQ(seqs(reader_->received_after(0, {"a.A", "b.B"}, 2, 10)), (std::vector<int64_t>{1, 2}));
}

TEST_F(ReceivedSequenceTest, WhenCommittedRunsOnceEarlierRecordsAreReadable) {
  journal_->record(received(1, "a.A", 2, "1"));
  std::promise<size_t> seen;
  journal_->when_committed([&](std::exception_ptr error) {
    EXPECT_FALSE(error);
    seen.set_value(1);
  });
  seen.get_future().get();
  EXPECT_EQ(seqs(reader_->received_after(0, {}, std::nullopt, 10)), (std::vector<int64_t>{1}));
}

}  // namespace
}  // namespace acomms::queue
