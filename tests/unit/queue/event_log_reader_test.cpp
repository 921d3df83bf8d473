// EventLogReader (daemon/queue/event_log_reader.h) over a real store:
// events written by the SqliteJournal through the group-commit writer, read
// back on the reader's own connection with every filter, oldest first, with
// `limit` keeping the newest.

#include "queue/event_log_reader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "queue/sqlite_journal.h"
#include "store/group_commit_writer.h"
#include "store/store.h"
#include "store/store_error.h"
#include "store_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;

constexpr double kT = 1'700'000'000;
constexpr uint64_t kBigFrame = 0xFFFF'FFFF'FFFF'FFF0ull;  // past 2^63

QueueEvent event(double dt, QueueEventKind kind, const std::string& type, int64_t message_id,
                 uint64_t frame_id = 0, int32_t src = -1, int32_t dest = -1, const std::string& detail = "") {
  QueueEvent e;
  e.kind = kind;
  e.time = kT + dt;
  e.type = type;
  e.message_id = message_id;
  e.frame_id = frame_id;
  e.src = src;
  e.dest = dest;
  e.detail = detail;
  return e;
}

class EventLogReaderTest : public acomms::testing::StoreFixture {
 protected:
  void SetUp() override {
    open_store();
    reader_ = std::make_unique<EventLogReader>(store_->db().path());
  }
  void TearDown() override {
    reader_.reset();
    close_store();
  }

  // The ten events most tests query (index = position in this list).
  void write_standard() {
    const std::vector<QueueEvent> events = {
        event(0, QueueEventKind::kQueued, "a.A", 1),
        event(1, QueueEventKind::kQueued, "b.B", 2),
        event(2, QueueEventKind::kSent, "a.A", 1, 100, 1, 2, "awaiting ack"),
        event(3, QueueEventKind::kAcked, "a.A", 1, 100, 1, 2),
        event(4, QueueEventKind::kReceived, "b.B", 0, 0, 5, 1),
        event(5, QueueEventKind::kDropped, "b.B", 2, 0, 1, 0, "queue full: oldest dropped"),
        event(5, QueueEventKind::kExpired, "a.A", 3, 0, 1, 2, "ttl passed"),
        event(7, QueueEventKind::kRetry, "a.A", 4, kBigFrame, 1, 2, "not acknowledged"),
        event(8, QueueEventKind::kSent, "b.B", 5, 101, 1, 0),
        event(9, QueueEventKind::kQueued, "a.A", 6, 0, 1, 2),
    };
    for (const QueueEvent& e : events) journal_->record(e);
    journal_->flush();
  }

  EventPage query(EventQuery q) { return reader_->query(q); }

  // The standard events in a page, as their indexes in write_standard()
  // (recognised by time offset and kind).
  static std::vector<int> indexes(const EventPage& page) {
    std::vector<int> out;
    for (const LoggedEvent& logged : page.events) {
      int dt = static_cast<int>(logged.event.time - kT);
      int index = dt;
      if (dt == 5) index = logged.event.kind == QueueEventKind::kDropped ? 5 : 6;
      out.push_back(index);
    }
    return out;
  }

  std::unique_ptr<EventLogReader> reader_;
};

using Ints = std::vector<int>;

TEST_F(EventLogReaderTest, AllEventsOldestFirstWithTheirFields) {
  write_standard();
  EventPage page = query({});
  EXPECT_FALSE(page.truncated);
  EXPECT_EQ(indexes(page), (Ints{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  for (size_t i = 1; i < page.events.size(); ++i) {
    EXPECT_GT(page.events[i].id, page.events[i - 1].id);
    EXPECT_GE(page.events[i].event.time, page.events[i - 1].event.time);
  }
  ASSERT_EQ(page.events.size(), 10u);
  const QueueEvent& queued = page.events[0].event;
  EXPECT_EQ(queued.kind, QueueEventKind::kQueued);
  EXPECT_EQ(queued.type, "a.A");
  EXPECT_EQ(queued.message_id, 1);
  EXPECT_EQ(queued.frame_id, 0u);
  EXPECT_EQ(queued.src, -1);
  EXPECT_EQ(queued.dest, -1);
  EXPECT_EQ(queued.detail, "");
  EXPECT_DOUBLE_EQ(queued.time, kT);

  const QueueEvent& sent = page.events[2].event;
  EXPECT_EQ(sent.kind, QueueEventKind::kSent);
  EXPECT_EQ(sent.frame_id, 100u);
  EXPECT_EQ(sent.src, 1);
  EXPECT_EQ(sent.dest, 2);
  EXPECT_EQ(sent.detail, "awaiting ack");

  const QueueEvent& received = page.events[4].event;
  EXPECT_EQ(received.kind, QueueEventKind::kReceived);
  EXPECT_EQ(received.message_id, 0);
  EXPECT_EQ(received.src, 5);
  EXPECT_EQ(received.dest, 1);

  EXPECT_EQ(page.events[5].event.dest, 0) << "broadcast (0) is not 'none'";
  EXPECT_EQ(page.events[7].event.frame_id, kBigFrame) << "a frame id past 2^63 did not survive";
}

TEST_F(EventLogReaderTest, EventsAtTheSameTimeKeepTheirWrittenOrder) {
  write_standard();
  EventPage page = query({});
  ASSERT_EQ(page.events.size(), 10u);
  EXPECT_EQ(page.events[5].event.kind, QueueEventKind::kDropped);
  EXPECT_EQ(page.events[6].event.kind, QueueEventKind::kExpired);
}

TEST_F(EventLogReaderTest, SinceAndUntilAreInclusive) {
  write_standard();
  EventQuery q;
  q.since = kT + 2;
  q.until = kT + 5;
  EXPECT_EQ(indexes(query(q)), (Ints{2, 3, 4, 5, 6}));
  EventQuery since_only;
  since_only.since = kT + 7;
  EXPECT_EQ(indexes(query(since_only)), (Ints{7, 8, 9}));
  EventQuery until_only;
  until_only.until = kT + 1.5;
  EXPECT_EQ(indexes(query(until_only)), (Ints{0, 1}));
  EventQuery empty;
  empty.since = kT + 5.5;
  empty.until = kT + 6.5;
  EventPage none = query(empty);
  EXPECT_TRUE(none.events.empty());
  EXPECT_FALSE(none.truncated);
}

TEST_F(EventLogReaderTest, FiltersByKindsTypesAndMessageId) {
  write_standard();
  EventQuery kinds;
  kinds.kinds = {"sent", "acked"};
  EXPECT_EQ(indexes(query(kinds)), (Ints{2, 3, 8}));
  EventQuery types;
  types.types = {"b.B"};
  EXPECT_EQ(indexes(query(types)), (Ints{1, 4, 5, 8}));
  EventQuery both;
  both.kinds = {"queued"};
  both.types = {"a.A"};
  EXPECT_EQ(indexes(query(both)), (Ints{0, 9}));
  EventQuery two_types;
  two_types.types = {"a.A", "b.B"};
  EXPECT_EQ(query(two_types).events.size(), 10u);
  EventQuery unknown_type;
  unknown_type.types = {"c.C"};
  EXPECT_TRUE(query(unknown_type).events.empty());
  EventQuery message;
  message.message_id = 1;
  EXPECT_EQ(indexes(query(message)), (Ints{0, 2, 3}));
  EventQuery everything;
  everything.since = kT + 1;
  everything.until = kT + 8;
  everything.kinds = {"sent", "dropped"};
  everything.types = {"b.B"};
  everything.message_id = 2;
  EXPECT_EQ(indexes(query(everything)), (Ints{5}));
}

TEST_F(EventLogReaderTest, LimitKeepsTheNewestAndSaysSo) {
  write_standard();
  EventQuery three;
  three.limit = 3;
  EventPage page = query(three);
  EXPECT_TRUE(page.truncated);
  EXPECT_EQ(indexes(page), (Ints{7, 8, 9}));

  EventQuery exact;
  exact.limit = 10;
  page = query(exact);
  EXPECT_FALSE(page.truncated) << "nothing more matched";
  EXPECT_EQ(page.events.size(), 10u);

  EventQuery nine;
  nine.limit = 9;
  page = query(nine);
  EXPECT_TRUE(page.truncated);
  EXPECT_EQ(indexes(page), (Ints{1, 2, 3, 4, 5, 6, 7, 8, 9}));

  EventQuery filtered;
  filtered.kinds = {"queued"};
  filtered.limit = 2;
  page = query(filtered);
  EXPECT_TRUE(page.truncated);
  EXPECT_EQ(indexes(page), (Ints{1, 9}));

  EventQuery one_same_time;  // of the two at +5, the later written is the newer
  one_same_time.until = kT + 5;
  one_same_time.limit = 1;
  EXPECT_EQ(indexes(query(one_same_time)), (Ints{6}));
}

TEST_F(EventLogReaderTest, UnknownKindThrowsListingTheKinds) {
  write_standard();
  EventQuery q;
  q.kinds = {"sent", "bogus"};
  try {
    query(q);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("bogus"), std::string::npos) << what;
    for (const char* kind : {"queued", "sent", "acked", "expired", "dropped", "retry", "received", "packet"}) {
      EXPECT_NE(what.find(kind), std::string::npos) << kind << " not listed: " << what;
    }
  }
  EXPECT_THROW(event_kind_from_string("Queued"), std::invalid_argument) << "kinds are lower case";
  EXPECT_THROW(event_kind_from_string(""), std::invalid_argument);
}

TEST_F(EventLogReaderTest, KindNamesRoundTrip) {
  for (QueueEventKind kind : {QueueEventKind::kQueued, QueueEventKind::kSent, QueueEventKind::kAcked,
                              QueueEventKind::kExpired, QueueEventKind::kDropped, QueueEventKind::kRetry,
                              QueueEventKind::kReceived, QueueEventKind::kPacket}) {
    EXPECT_EQ(event_kind_from_string(std::string(to_string(kind))), kind) << to_string(kind);
  }
}

TEST_F(EventLogReaderTest, EmptyLogAndLaterWritesAreSeen) {
  EventPage empty = query({});
  EXPECT_TRUE(empty.events.empty());
  EXPECT_FALSE(empty.truncated);
  // The reader was opened before anything was written: it still sees what
  // the writer commits afterwards (WAL).
  write_standard();
  EXPECT_EQ(query({}).events.size(), 10u);
  journal_->record(event(20, QueueEventKind::kExpired, "b.B", 7));
  journal_->flush();
  EventPage later = query({});
  ASSERT_EQ(later.events.size(), 11u);
  EXPECT_EQ(later.events.back().event.message_id, 7);
}

TEST_F(EventLogReaderTest, EventsSurviveReopeningTheStore) {
  write_standard();
  reader_.reset();
  journal_.reset();
  writer_.reset();
  store_.reset();
  store_ = std::make_unique<store::Store>((dir_ / "data").string());
  EventLogReader reader(store_->db().path());
  EXPECT_EQ(indexes(reader.query({})), (Ints{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
}

TEST_F(EventLogReaderTest, MissingStoreIsAStoreError) {
  EXPECT_THROW(EventLogReader((dir_ / "nowhere" / "acommsd.db").string()), store::StoreError);
}

}  // namespace
}  // namespace acomms::queue
