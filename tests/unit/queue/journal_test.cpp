// The SQLite message journal and the group-commit writer under it: ids,
// what survives a reopen, events and removals in one transaction, ordering,
// concurrent appends sharing commits, and failures confined to their own
// request (or, for a failed COMMIT, reported to every request of the batch).

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <future>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "queue/sqlite_journal.h"
#include "store/group_commit_writer.h"
#include "store/store.h"
#include "store_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;
using store::Database;
using store::GroupCommitWriter;
using store::Statement;
using store::StoreError;

class JournalTest : public acomms::testing::StoreFixture {
 protected:
  void SetUp() override { open(); }

  // The store in the test's directory itself (not a data/ under it).
  void open() { open_store(dir_.path()); }
  void reopen() {
    close_store();
    open();
  }
  SqliteJournal& journal() { return *journal_; }
  GroupCommitWriter& writer() { return *writer_; }

  // Queries run on the writer thread: the only one allowed on the connection.
  int64_t count(const std::string& sql) {
    return writer()
        .submit([sql](Database& db) {
          Statement query = db.prepare(sql);
          query.step();
          return query.column_int64(0);
        })
        .get();
  }
  void exec(const std::string& sql) {
    writer().submit([sql](Database& db) { db.exec(sql); }).get();
  }
};

JournalMessage message(const std::string& tag) {
  JournalMessage m;
  m.type = "test.Message";
  m.payload = tag;
  m.src = 1;
  m.dest = 2;
  m.submitted_at = 1'700'000'000.25;
  m.ttl_s = 30;
  return m;
}

QueueEvent removal(int64_t id, QueueEventKind kind = QueueEventKind::kAcked) {
  QueueEvent event;
  event.kind = kind;
  event.time = 1'700'000'100.5;
  event.type = "test.Message";
  event.message_id = id;
  event.removes_message = true;
  return event;
}

TEST_F(JournalTest, AppendReturnsIncreasingIds) {
  int64_t previous = 0;
  for (int i = 0; i < 20; ++i) {
    int64_t id = journal().append(message(std::to_string(i)));
    EXPECT_GT(id, previous);
    previous = id;
  }
}

TEST_F(JournalTest, LoadAfterReopenReturnsTheRemainingMessagesIntact) {
  JournalMessage odd;
  odd.type = "goby.acomms.protobuf.NavigationReport";
  odd.payload = std::string("\x00\x01\xff\x00zz", 6);  // binary, with NULs
  odd.src = -1;
  odd.dest = 0;
  odd.submitted_at = 1'700'000'123.456789;
  odd.ttl_s = 0.125;
  JournalMessage empty = message("");  // an all-defaults protobuf serializes to nothing
  int64_t kept1 = journal().append(odd);
  int64_t removed = journal().append(message("gone"));
  int64_t kept2 = journal().append(empty);
  journal().record(removal(removed));
  journal().flush();
  reopen();

  std::vector<JournalMessage> loaded = journal().load();
  ASSERT_EQ(loaded.size(), 2u);
  EXPECT_EQ(loaded[0].id, kept1);
  EXPECT_EQ(loaded[0].type, odd.type);
  EXPECT_EQ(loaded[0].payload, odd.payload);
  EXPECT_EQ(loaded[0].src, -1);
  EXPECT_EQ(loaded[0].dest, 0);
  EXPECT_DOUBLE_EQ(loaded[0].submitted_at, odd.submitted_at);
  EXPECT_DOUBLE_EQ(loaded[0].ttl_s, 0.125);
  EXPECT_EQ(loaded[1].id, kept2);
  EXPECT_EQ(loaded[1].payload, "");
  EXPECT_EQ(loaded[1].src, 1);
  EXPECT_EQ(loaded[1].dest, 2);
  EXPECT_DOUBLE_EQ(loaded[1].ttl_s, 30);
}

TEST_F(JournalTest, IdsAreNeverReusedAfterTheNewestMessageIsRemoved) {
  journal().append(message("a"));
  int64_t newest = journal().append(message("b"));
  journal().record(removal(newest));
  journal().flush();
  reopen();
  // A plain rowid would hand out `newest` again: acks for the old message
  // would then remove the new one.
  EXPECT_GT(journal().append(message("c")), newest);
}

TEST_F(JournalTest, EventRowsHoldEveryFieldAndNullForNone) {
  QueueEvent sent;
  sent.kind = QueueEventKind::kSent;
  sent.time = 1'700'000'200.75;
  sent.type = "test.Message";
  sent.message_id = journal().append(message("x"));
  sent.frame_id = 77;
  sent.src = 3;
  sent.dest = 4;
  sent.detail = "slot 2";
  journal().record(sent);
  QueueEvent received;
  received.kind = QueueEventKind::kReceived;
  received.time = 1'700'000'201;
  received.type = "test.Other";
  journal().record(received);  // message_id 0, frame_id 0, src/dest -1: none
  journal().flush();

  struct Row {
    double time;
    std::string kind, type, detail;
    bool message_null, frame_null, src_null, dest_null;
    int64_t message_id, frame_id, src, dest;
  };
  auto rows = writer()
                  .submit([](Database& db) {
                    std::vector<Row> rows;
                    Statement q = db.prepare(
                        "SELECT time, kind, type, message_id, frame_id, src, dest, detail "
                        "FROM event_log WHERE kind != 'queued' ORDER BY id");
                    while (q.step()) {
                      rows.push_back({q.column_double(0), q.column_text(1), q.column_text(2),
                                      q.column_text(7), q.is_null(3), q.is_null(4), q.is_null(5),
                                      q.is_null(6), q.column_int64(3), q.column_int64(4),
                                      q.column_int64(5), q.column_int64(6)});
                    }
                    return rows;
                  })
                  .get();
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0].time, sent.time);
  EXPECT_EQ(rows[0].kind, "sent");
  EXPECT_EQ(rows[0].type, "test.Message");
  EXPECT_EQ(rows[0].message_id, sent.message_id);
  EXPECT_EQ(rows[0].frame_id, 77);
  EXPECT_EQ(rows[0].src, 3);
  EXPECT_EQ(rows[0].dest, 4);
  EXPECT_EQ(rows[0].detail, "slot 2");
  EXPECT_EQ(rows[1].kind, "received");
  EXPECT_EQ(rows[1].type, "test.Other");
  EXPECT_TRUE(rows[1].message_null);
  EXPECT_TRUE(rows[1].frame_null);
  EXPECT_TRUE(rows[1].src_null);
  EXPECT_TRUE(rows[1].dest_null);
  EXPECT_EQ(rows[1].detail, "");
  // An event that does not end the message's life leaves it queued.
  EXPECT_EQ(journal().load().size(), 1u);
}

TEST_F(JournalTest, ReceivedSinceGivesReceivedEventsWithTheirBytesOldestFirstAfterReopen) {
  auto event = [](QueueEventKind kind, double time, int32_t src, std::string encoded) {
    QueueEvent e;
    e.kind = kind;
    e.time = time;
    e.type = "test.Message";
    e.src = src;
    e.dest = 1;
    e.encoded = std::move(encoded);
    return e;
  };
  const std::string with_nul("\x04\x00\xff", 3);
  journal().record(event(QueueEventKind::kReceived, 1000, 4, "too old"));
  journal().record(event(QueueEventKind::kReceived, 1070, 5, "second"));
  journal().record(event(QueueEventKind::kReceived, 1060, 4, with_nul));  // logged late, earlier time
  journal().record(event(QueueEventKind::kSent, 1065, 4, ""));
  journal().record(event(QueueEventKind::kReceived, 1066, 4, ""));  // from before the bytes were kept
  journal().flush();
  reopen();
  std::vector<QueueEvent> received = journal().received_since(1050);
  ASSERT_EQ(received.size(), 2u);
  EXPECT_EQ(received[0].kind, QueueEventKind::kReceived);
  EXPECT_DOUBLE_EQ(received[0].time, 1060);
  EXPECT_EQ(received[0].src, 4);
  EXPECT_EQ(received[0].dest, 1);
  EXPECT_EQ(received[0].type, "test.Message");
  EXPECT_EQ(received[0].encoded, with_nul);
  EXPECT_DOUBLE_EQ(received[1].time, 1070);
  EXPECT_EQ(received[1].src, 5);
  EXPECT_EQ(received[1].encoded, "second");
}

// Authenticated messages accepted (migrations/0009_auth_accepted.sql): kept
// with their received event, read back after a reopen by stamp, and
// forgotten once stamped before the event's auth_forget_before.
TEST_F(JournalTest, AuthenticatedAcceptedAreKeptWithTheirEventAndForgottenPastTheWindow) {
  auto accepted = [](uint32_t sent, std::string encoded, double forget_before) {
    QueueEvent e;
    e.kind = QueueEventKind::kReceived;
    e.time = sent + 1.0;
    e.type = "test.Command";
    e.encoded = std::move(encoded);
    e.auth_sent_s = sent;
    e.auth_forget_before = forget_before;
    return e;
  };
  const std::string with_nul("\x0a\x00\x7e", 3);
  journal().record(accepted(1000, "first", 0));
  journal().record(accepted(1500, with_nul, 0));
  QueueEvent plain;  // not authenticated: no row
  plain.kind = QueueEventKind::kReceived;
  plain.type = "test.Note";
  plain.encoded = "note";
  journal().record(plain);
  journal().flush();
  reopen();
  std::vector<QueueEvent> kept = journal().authenticated_since(0);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].type, "test.Command");
  EXPECT_EQ(kept[0].encoded, "first");
  EXPECT_EQ(kept[0].auth_sent_s, 1000u);
  EXPECT_EQ(kept[1].encoded, with_nul);
  EXPECT_EQ(journal().authenticated_since(1200).size(), 1u);
  EXPECT_EQ(count("SELECT COUNT(*) FROM event_log WHERE kind = 'received'"), 3);
  // The next one forgets what was stamped before 1200.
  journal().record(accepted(1800, "third", 1200));
  journal().flush();
  EXPECT_EQ(count("SELECT COUNT(*) FROM auth_accepted"), 2);
  EXPECT_EQ(count("SELECT MIN(sent_s) FROM auth_accepted"), 1500);
}

TEST_F(JournalTest, RemovalAndItsEventAreStoredTogetherOrNotAtAll) {
  int64_t a = journal().append(message("a"));
  int64_t b = journal().append(message("b"));
  // Make the event insert fail for `a`, and the delete fail for `b`: in both
  // cases neither half may remain.
  exec("CREATE TEMP TRIGGER fail_event BEFORE INSERT ON event_log WHEN NEW.detail = 'boom' "
       "BEGIN SELECT RAISE(ABORT, 'event refused'); END;"
       "CREATE TEMP TRIGGER fail_delete BEFORE DELETE ON queued_messages WHEN OLD.id = " +
       std::to_string(b) + " BEGIN SELECT RAISE(ABORT, 'delete refused'); END;");
  QueueEvent bad_event = removal(a);
  bad_event.detail = "boom";
  journal().record(bad_event);
  journal().record(removal(b));
  journal().flush();
  EXPECT_EQ(count("SELECT count(*) FROM event_log WHERE kind != 'queued'"), 0);
  EXPECT_EQ(count("SELECT count(*) FROM queued_messages"), 2);

  // And when both halves succeed, both are there.
  journal().record(removal(a, QueueEventKind::kExpired));
  journal().flush();
  EXPECT_EQ(count("SELECT count(*) FROM event_log WHERE kind = 'expired'"), 1);
  std::vector<JournalMessage> left = journal().load();
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left[0].id, b);
}

TEST_F(JournalTest, RecordIsAppliedAfterTheAppendBeforeIt) {
  // No flush between append and record: only the writer's FIFO order keeps
  // the delete from running before the insert it deletes.
  for (int i = 0; i < 50; ++i) {
    int64_t id = journal().append(message("m"));
    journal().record(removal(id));
  }
  journal().flush();
  EXPECT_TRUE(journal().load().empty());
  EXPECT_EQ(count("SELECT count(*) FROM event_log WHERE kind = 'queued'"), 50);
  EXPECT_EQ(count("SELECT count(*) FROM event_log WHERE kind = 'acked'"), 50);
}

TEST_F(JournalTest, AppendLogsTheQueuedEventInTheSameCommit) {
  JournalMessage m = message("q");
  m.src = 3;
  m.dest = 4;
  m.submitted_at = 1234.5;
  int64_t id = journal().append(m);
  // No flush: append() returned, so its commit (and the event in it) is done.
  EXPECT_EQ(count("SELECT count(*) FROM event_log WHERE kind = 'queued' AND message_id = " + std::to_string(id) +
                  " AND src = 3 AND dest = 4 AND time = 1234.5 AND type = 'test.Message'"),
            1);
}

TEST_F(JournalTest, ConcurrentAppendsGetUniqueIds) {
  constexpr int kThreads = 16;
  constexpr int kEach = 100;
  std::vector<std::vector<int64_t>> ids(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < kEach; ++i) {
        ids[t].push_back(journal().append(message(std::to_string(t) + ":" + std::to_string(i))));
      }
    });
  }
  for (auto& thread : threads) thread.join();

  std::set<int64_t> unique;
  for (const auto& per_thread : ids) {
    EXPECT_TRUE(std::is_sorted(per_thread.begin(), per_thread.end()));
    unique.insert(per_thread.begin(), per_thread.end());
  }
  EXPECT_EQ(unique.size(), static_cast<size_t>(kThreads * kEach));
  GroupCommitWriter::Stats stats = writer().stats();
  EXPECT_EQ(stats.failed, 0u);
  EXPECT_GE(stats.committed, static_cast<uint64_t>(kThreads * kEach));
  // Whether these threads happened to share commits depends on scheduling;
  // that requests queued during a batch do share the next one is proven
  // deterministically with WriterGate below.
  EXPECT_EQ(journal().load().size(), static_cast<size_t>(kThreads * kEach));
}

// Holds the writer thread inside a batch until released, so that requests
// queued meanwhile are certain to share the next batch.
class WriterGate {
 public:
  explicit WriterGate(GroupCommitWriter& writer) {
    done_ = writer.submit([this](Database&) {
      entered_.set_value();
      release_.get_future().wait();
    });
    entered_.get_future().wait();
  }
  void open() {
    release_.set_value();
    done_.get();
  }

 private:
  std::promise<void> entered_, release_;
  std::future<void> done_;
};

TEST_F(JournalTest, AFailingWriteRollsBackOnlyItself) {
  exec("CREATE TABLE t (v TEXT)");
  WriterGate gate(writer());
  auto insert = [](std::string v) {
    return [v](Database& db) { db.prepare("INSERT INTO t VALUES ('" + v + "')").step(); };
  };
  auto first = writer().submit(insert("first"));
  auto bad = writer().submit([](Database& db) {
    db.prepare("INSERT INTO t VALUES ('half done')").step();
    throw std::runtime_error("request refused");
  });
  writer().post([](Database&) { throw std::runtime_error("posted write refused (expected in this test)"); });
  auto last = writer().submit([](Database& db) {
    db.prepare("INSERT INTO t VALUES ('last')").step();
    return 42;
  });
  gate.open();

  EXPECT_NO_THROW(first.get());
  EXPECT_THROW(
      {
        try {
          bad.get();
        } catch (const std::runtime_error& e) {
          EXPECT_STREQ(e.what(), "request refused");
          throw;
        }
      },
      std::runtime_error);
  EXPECT_EQ(last.get(), 42);
  EXPECT_EQ(count("SELECT count(*) FROM t"), 2);
  EXPECT_EQ(count("SELECT count(*) FROM t WHERE v = 'half done'"), 0);
  GroupCommitWriter::Stats stats = writer().stats();
  EXPECT_EQ(stats.failed, 2u);
  EXPECT_GE(stats.max_batch, 4u);  // first, bad, posted, last: one transaction
}

TEST_F(JournalTest, AFailedCommitFailsEveryRequestOfItsBatch) {
  // A deferred foreign key is checked only at COMMIT: one bad row makes the
  // whole transaction fail there, after every request's work succeeded.
  exec("CREATE TABLE parent (id INTEGER PRIMARY KEY);"
       "CREATE TABLE child (parent_id INTEGER REFERENCES parent(id) DEFERRABLE INITIALLY DEFERRED)");
  WriterGate gate(writer());
  auto good = writer().submit([](Database& db) { db.exec("INSERT INTO parent VALUES (1)"); });
  auto orphan = writer().submit([](Database& db) { db.exec("INSERT INTO child VALUES (99)"); });
  gate.open();
  EXPECT_THROW(good.get(), StoreError);
  EXPECT_THROW(orphan.get(), StoreError);
  // Nothing of that batch is stored, and the writer carries on.
  EXPECT_EQ(count("SELECT count(*) FROM parent"), 0);
  EXPECT_EQ(count("SELECT count(*) FROM child"), 0);
  EXPECT_GT(journal().append(message("after")), 0);
}

TEST_F(JournalTest, StopDrainsQueuedWritesThenRefusesMore) {
  for (int i = 0; i < 100; ++i) {
    int64_t id = journal().append(message("m"));
    if (i % 2 == 0) journal().record(removal(id));
  }
  writer().stop();  // no flush: stop itself must drain
  EXPECT_FALSE(writer().running());
  EXPECT_THROW(journal().append(message("late")), StoreError);
  EXPECT_THROW(journal().record(removal(1)), StoreError);
  reopen();
  EXPECT_EQ(journal().load().size(), 50u);
}

// The append a gRPC Submit uses: it must not report an id before the
// commit, must report it from the writer thread (never the caller's), and
// must report a failed commit instead of an id.
struct Reported {
  std::promise<std::pair<int64_t, std::exception_ptr>> promise;
  std::thread::id thread;
  MessageJournal::Appended callback() {
    return [this](int64_t id, std::exception_ptr error) {
      thread = std::this_thread::get_id();
      promise.set_value({id, error});
    };
  }
};

TEST_F(JournalTest, AppendWithoutWaitingReportsTheIdOnlyAfterTheCommit) {
  Reported reported;
  auto result = reported.promise.get_future();
  {
    WriterGate gate(writer());
    journal().append(message("async"), reported.callback());
    EXPECT_EQ(result.wait_for(std::chrono::milliseconds(50)), std::future_status::timeout);
    gate.open();
  }
  auto [id, error] = result.get();
  EXPECT_EQ(error, nullptr);
  EXPECT_GT(id, 0);
  EXPECT_NE(reported.thread, std::this_thread::get_id());
  std::vector<JournalMessage> stored = journal().load();
  ASSERT_EQ(stored.size(), 1u);
  EXPECT_EQ(stored[0].id, id);
  EXPECT_EQ(stored[0].payload, "async");
  EXPECT_EQ(count("SELECT count(*) FROM event_log WHERE kind = 'queued' AND message_id = " + std::to_string(id)), 1);
}

TEST_F(JournalTest, AppendWithoutWaitingReportsAFailedCommitInsteadOfAnId) {
  exec("CREATE TABLE child (parent_id INTEGER REFERENCES queued_messages(id) DEFERRABLE INITIALLY DEFERRED)");
  Reported reported;
  auto result = reported.promise.get_future();
  {
    WriterGate gate(writer());
    auto orphan = writer().submit([](Database& db) { db.exec("INSERT INTO child VALUES (987654)"); });
    journal().append(message("lost with its batch"), reported.callback());
    gate.open();
    EXPECT_THROW(orphan.get(), StoreError);
  }
  auto [id, error] = result.get();
  EXPECT_EQ(id, 0);
  ASSERT_NE(error, nullptr);
  EXPECT_THROW(std::rethrow_exception(error), StoreError);
  EXPECT_TRUE(journal().load().empty());
}

TEST_F(JournalTest, AppendsWithoutWaitingCompleteInTheOrderMade) {
  constexpr int kAppends = 200;
  std::vector<int64_t> ids;
  std::mutex mutex;
  std::promise<void> all;
  for (int i = 0; i < kAppends; ++i) {
    journal().append(message(std::to_string(i)), [&](int64_t id, std::exception_ptr error) {
      std::lock_guard lock(mutex);
      ids.push_back(error ? -1 : id);
      if (ids.size() == kAppends) all.set_value();
    });
  }
  all.get_future().get();
  EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
  EXPECT_EQ(std::set<int64_t>(ids.begin(), ids.end()).size(), static_cast<size_t>(kAppends));
  EXPECT_GT(ids.front(), 0);
  std::vector<JournalMessage> stored = journal().load();
  ASSERT_EQ(stored.size(), static_cast<size_t>(kAppends));
  for (int i = 0; i < kAppends; ++i) {
    EXPECT_EQ(stored[i].id, ids[i]);
    EXPECT_EQ(stored[i].payload, std::to_string(i));
  }
}

TEST_F(JournalTest, AThrowingCompletionDoesNotStopTheWriter) {
  writer().post([](Database&) {}, [](std::exception_ptr) {
    throw std::runtime_error("completion failed (expected in this test)");
  });
  EXPECT_GT(journal().append(message("after")), 0);
  EXPECT_TRUE(writer().running());
  EXPECT_THROW(writer().post([](Database&) {}, GroupCommitWriter::Done{}), StoreError);
}

TEST_F(JournalTest, AppendWithoutWaitingToAStoppedWriterThrowsAndNeverReports) {
  writer().stop();
  bool reported = false;
  EXPECT_THROW(journal().append(message("late"), [&](int64_t, std::exception_ptr) { reported = true; }),
               StoreError);
  EXPECT_FALSE(reported);
}

TEST_F(JournalTest, PreparedIsOnlyForTheWriterThread) {
  EXPECT_THROW(writer().prepared("SELECT 1"), StoreError);
}

TEST(QueueEventKindTest, NamesAreTheWordsStoredInTheLog) {
  EXPECT_EQ(to_string(QueueEventKind::kQueued), "queued");
  EXPECT_EQ(to_string(QueueEventKind::kSent), "sent");
  EXPECT_EQ(to_string(QueueEventKind::kAcked), "acked");
  EXPECT_EQ(to_string(QueueEventKind::kExpired), "expired");
  EXPECT_EQ(to_string(QueueEventKind::kDropped), "dropped");
  EXPECT_EQ(to_string(QueueEventKind::kRetry), "retry");
  EXPECT_EQ(to_string(QueueEventKind::kReceived), "received");
}

}  // namespace
}  // namespace acomms::queue
