// Submit when the store's disk fails mid-batch: a BEGIN, a write inside a
// request's savepoint, or the COMMIT, each failed by the fault-injecting VFS
// under the real SQLite journal, group-commit writer and a running core.
//
// The promises: every Submit of a failed batch is answered with an error
// naming the store (UNAVAILABLE, or RESOURCE_EXHAUSTED saying the disk is
// full); no Submit is answered with an id whose row is not in the store
// afterwards; the queue in memory holds exactly the store's rows; and once
// the disk works again, Submits succeed: the writer survived and holds no
// transaction open.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/clock.h"
#include "core/event_loop.h"
#include "dccl/codec.h"
#include "faulty_vfs.h"
#include "queue/durable_receipts.h"
#include "queue/queue_manager.h"
#include "queue/sqlite_journal.h"
#include "queue/submitter.h"
#include "store/group_commit_writer.h"
#include "store/sqlite.h"
#include "store/store.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;
using namespace std::chrono_literals;
using store::testing::FaultyVfs;
using store::testing::ScopedVfsFault;
using store::testing::VfsCall;
using store::testing::VfsFault;
using store::testing::VfsFile;
using Error = SubmitResult::Error;

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package qf;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional int32 dest = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 2 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

constexpr auto kPatience = 10s;  // a bound on waiting for an event, never a sleep
constexpr int kBatch = 5;        // Submits made while the writer is held: one batch

class SubmitFaultTest : public ::testing::Test {
 protected:
  void SetUp() override {
    FaultyVfs::instance();
    dir_ = fs::temp_directory_path() / ("acomms-submit-fault-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "qf.proto") << kProto;
    codec_.load((dir_ / "qf.proto").string());

    store_ = std::make_unique<store::Store>((dir_ / "data").string(), store::Store::Options{FaultyVfs::kName});
    path_ = store_->db().path();
    // A small page cache makes a large write spill to the WAL inside its
    // own savepoint, before the COMMIT: the mid-batch write a fault can hit.
    store_->db().exec("PRAGMA cache_size=10; CREATE TABLE ballast (bytes BLOB)");
    writer_ = std::make_unique<store::GroupCommitWriter>(store_->db());
    journal_ = std::make_unique<SqliteJournal>(*writer_);
    v1::QueueConfig config;
    ASSERT_TRUE(pb::TextFormat::ParseFromString(R"(type { type: "qf.Status" roles { destination_field: "dest" } })",
                                                &config));
    queues_ = std::make_unique<QueueManager>(codec_, config, 1, clock_, *journal_);
    core_ = std::make_unique<core::EventLoop>();
    submitter_ = std::make_unique<Submitter>(
        *queues_, [core = core_.get()](std::function<void()> work) { core->post(std::move(work)); });
    core_->start();
  }

  void TearDown() override {
    FaultyVfs::instance().disarm();
    close();
    fs::remove_all(dir_);
  }

  // Stops everything in the daemon's order; the store is then closed.
  void close() {
    if (core_) core_->stop();
    submitter_.reset();
    queues_.reset();
    if (writer_) writer_->stop();
    journal_.reset();
    writer_.reset();
    store_.reset();
    core_.reset();
  }

  std::future<SubmitResult> submit(int value) {
    auto message = codec_.new_message("qf.Status");
    EXPECT_TRUE(pb::TextFormat::ParseFromString("value: " + std::to_string(value), message.get()));
    auto promise = std::make_shared<std::promise<SubmitResult>>();
    auto answers = std::make_shared<std::atomic<int>>(0);
    std::future<SubmitResult> future = promise->get_future();
    submitter_->submit(*message, 0, [promise, answers](SubmitResult result) {
      if (answers->fetch_add(1) > 0) {
        ADD_FAILURE() << "answered twice";
        return;
      }
      promise->set_value(std::move(result));
    });
    return future;
  }

  SubmitResult wait(std::future<SubmitResult> future) {
    if (future.wait_for(kPatience) != std::future_status::ready) {
      ADD_FAILURE() << "no answer within " << kPatience.count() << " s";
      return {Error::kStoreUnavailable, 0, "not answered"};
    }
    return future.get();
  }

  // Keeps the writer busy in a batch of its own until release(), so that
  // the Submits made meanwhile share the next batch, and a fault armed
  // meanwhile first meets that batch (the held batch writes nothing).
  struct Hold {
    std::promise<void> entered;
    std::promise<void> released;
    std::shared_future<void> release_signal = released.get_future().share();
    void release() { released.set_value(); }
  };
  std::shared_ptr<Hold> hold_writer() {
    auto hold = std::make_shared<Hold>();
    std::future<void> entered = hold->entered.get_future();
    writer_->post([hold](store::Database&) {
      hold->entered.set_value();
      hold->release_signal.wait_for(kPatience);
    });
    EXPECT_EQ(entered.wait_for(kPatience), std::future_status::ready) << "the writer never ran";
    return hold;
  }

  // kBatch Submits in one batch while `fault` is armed; their answers.
  std::vector<SubmitResult> submit_batch_under(const VfsFault& fault) {
    std::vector<std::future<SubmitResult>> futures;
    {
      auto hold = hold_writer();
      FaultyVfs::instance().arm(fault);
      for (int i = 0; i < kBatch; ++i) futures.push_back(submit(100 + i));
      hold->release();
    }
    std::vector<SubmitResult> results;
    for (auto& future : futures) results.push_back(wait(std::move(future)));
    EXPECT_GE(FaultyVfs::instance().failures(), 1) << "the fault never hit";
    FaultyVfs::instance().disarm();
    return results;
  }

  // The store's rows, read through a connection of its own on the default
  // VFS: only what is committed.
  std::set<int64_t> stored_ids() {
    store::Database reader(path_, store::Database::Mode::kReadOnly);
    store::Statement query = reader.prepare("SELECT id FROM queued_messages");
    std::set<int64_t> ids;
    while (query.step()) ids.insert(query.column_int64(0));
    return ids;
  }

  int64_t count(const std::string& sql) {
    store::Database reader(path_, store::Database::Mode::kReadOnly);
    store::Statement query = reader.prepare(sql);
    query.step();
    return query.column_int64(0);
  }

  // The ids in the queue in memory (what ListQueued shows).
  std::set<int64_t> queued_ids() {
    return core_->call([this] {
      std::set<int64_t> ids;
      for (const QueuedMessage& m : queues_->find_queue("qf.Status")->messages()) ids.insert(m.record.id);
      return ids;
    });
  }

  // Once the disk works again: a Submit succeeds, the queue matches the
  // store, no write transaction is left open (another connection can take
  // the write lock), and after a clean close every id answered is stored.
  void expect_serving_again_and_consistent(std::set<int64_t> answered) {
    std::future<SubmitResult> future = submit(7);
    SubmitResult after = wait(std::move(future));
    ASSERT_TRUE(after.ok()) << "the store did not recover: " << after.text;
    answered.insert(after.message_id);
    writer_->flush();
    EXPECT_TRUE(writer_->running());
    EXPECT_EQ(queued_ids(), stored_ids()) << "the queue in memory differs from the store";
    {
      store::Database other(path_);
      other.exec("BEGIN IMMEDIATE; ROLLBACK");  // fails (busy) if a transaction was stuck open
    }
    close();
    EXPECT_EQ(stored_ids(), answered) << "an id answered is missing from the store after closing it";
  }

  fs::path dir_;
  std::string path_;
  dccl::Codec codec_;
  core::SimulatedClock clock_{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
  std::unique_ptr<store::Store> store_;
  std::unique_ptr<store::GroupCommitWriter> writer_;
  std::unique_ptr<SqliteJournal> journal_;
  std::unique_ptr<QueueManager> queues_;
  std::unique_ptr<core::EventLoop> core_;
  std::unique_ptr<Submitter> submitter_;
};

// Every answer is the store's failure: UNAVAILABLE-kind, naming the file.
void expect_all_unavailable(const std::vector<SubmitResult>& results, const std::string& path,
                            const std::string& why) {
  ASSERT_EQ(results.size(), static_cast<size_t>(kBatch));
  for (const SubmitResult& r : results) {
    EXPECT_EQ(r.error, Error::kStoreUnavailable) << r.text;
    EXPECT_EQ(r.text.rfind("store: ", 0), 0u) << r.text;
    EXPECT_NE(r.text.find(path), std::string::npos) << "does not name the store: " << r.text;
    EXPECT_NE(r.text.find(why), std::string::npos) << r.text;
    EXPECT_NE(r.text.find("not stored"), std::string::npos) << r.text;
    EXPECT_EQ(r.message_id, 0);
  }
}

TEST_F(SubmitFaultTest, AFailedBeginFailsEverySubmitOfTheBatchAndTheNextBatchSucceeds) {
  ASSERT_TRUE(wait(submit(1)).ok());
  const std::set<int64_t> before = stored_ids();
  // BEGIN IMMEDIATE in WAL mode locks the wal-index: the call that fails.
  auto results = submit_batch_under({VfsCall::kShmLock, VfsFile::kAny, SQLITE_IOERR_SHMLOCK, 0, true});
  expect_all_unavailable(results, path_, "cannot start a transaction");
  EXPECT_EQ(stored_ids(), before);
  EXPECT_EQ(queued_ids(), before);
  expect_serving_again_and_consistent(before);
}

TEST_F(SubmitFaultTest, AFailedCommitWriteFailsEverySubmitOfTheBatch) {
  auto results = submit_batch_under({VfsCall::kWrite, VfsFile::kWal, SQLITE_IOERR_WRITE, 0, true});
  expect_all_unavailable(results, path_, "commit failed");
  EXPECT_EQ(count("SELECT COUNT(*) FROM event_log WHERE kind = 'queued'"), 0) << "an event outlived its message";
  EXPECT_TRUE(stored_ids().empty());
  EXPECT_TRUE(queued_ids().empty());
  expect_serving_again_and_consistent({});
}

TEST_F(SubmitFaultTest, AFailedCommitSyncFailsEverySubmitOfTheBatch) {
  // The WAL frames are written, only the fsync fails: still not durable,
  // so nobody may be told it is.
  auto results = submit_batch_under({VfsCall::kSync, VfsFile::kWal, SQLITE_IOERR_FSYNC, 0, true});
  expect_all_unavailable(results, path_, "commit failed");
  EXPECT_TRUE(stored_ids().empty());
  EXPECT_TRUE(queued_ids().empty());
  expect_serving_again_and_consistent({});
}

TEST_F(SubmitFaultTest, AFullDiskFailsEverySubmitWithResourceExhaustedNamingTheStore) {
  auto results = submit_batch_under({VfsCall::kWrite, VfsFile::kWal, SQLITE_FULL, 0, true});
  ASSERT_EQ(results.size(), static_cast<size_t>(kBatch));
  for (const SubmitResult& r : results) {
    EXPECT_EQ(r.error, Error::kStoreFull) << r.text;
    EXPECT_NE(r.text.find(path_), std::string::npos) << "does not name the store: " << r.text;
    EXPECT_NE(r.text.find("the disk holding the store is full"), std::string::npos) << r.text;
  }
  EXPECT_TRUE(stored_ids().empty());
  EXPECT_TRUE(queued_ids().empty());
  expect_serving_again_and_consistent({});
}

TEST_F(SubmitFaultTest, ACheckpointFailingAfterTheCommitLeavesTheSubmitsAnsweredAndStored) {
  // The commit is durable in the WAL; copying it into the main file (here
  // after every commit) is SQLite's own later business. Its failure must not
  // turn stored messages into errors: a client would submit them again.
  writer_->submit([](store::Database& db) { db.exec("PRAGMA wal_autocheckpoint=1"); }).get();
  auto results = submit_batch_under({VfsCall::kWrite, VfsFile::kMainDb, SQLITE_IOERR_WRITE, 0, true});
  std::set<int64_t> answered;
  for (const SubmitResult& r : results) {
    EXPECT_TRUE(r.ok()) << r.text;
    answered.insert(r.message_id);
  }
  EXPECT_EQ(answered.size(), static_cast<size_t>(kBatch));
  EXPECT_EQ(stored_ids(), answered);
  EXPECT_EQ(queued_ids(), answered);
  expect_serving_again_and_consistent(answered);
}

TEST_F(SubmitFaultTest, AWriteFailingInsideItsSavepointFailsItsTransactionAndTheRestCommit) {
  // Batch: two Submits, a large write that spills to the WAL and meets a
  // one-time I/O error (SQLite then rolls the whole transaction back), two
  // more Submits. The first two went down with the transaction; the last
  // two run in a fresh one and commit.
  std::vector<std::future<SubmitResult>> early;
  std::vector<std::future<SubmitResult>> late;
  std::future<void> ballast;
  {
    auto hold = hold_writer();
    FaultyVfs::instance().arm({VfsCall::kWrite, VfsFile::kWal, SQLITE_IOERR_WRITE, 0, false});
    early.push_back(submit(1));
    early.push_back(submit(2));
    ballast = writer_->submit([](store::Database& db) {
      db.exec("INSERT INTO ballast VALUES (randomblob(200000))");
    });
    late.push_back(submit(3));
    late.push_back(submit(4));
    hold->release();
  }
  ASSERT_EQ(ballast.wait_for(kPatience), std::future_status::ready);
  EXPECT_THROW(ballast.get(), store::StoreError);
  EXPECT_EQ(FaultyVfs::instance().failures(), 1) << "the write never spilled into the fault";
  std::vector<SubmitResult> lost;
  for (auto& f : early) lost.push_back(wait(std::move(f)));
  for (const SubmitResult& r : lost) {
    EXPECT_EQ(r.error, Error::kStoreUnavailable) << r.text;
    EXPECT_NE(r.text.find(path_), std::string::npos) << r.text;
    EXPECT_NE(r.text.find("rolled back"), std::string::npos) << r.text;
  }
  std::set<int64_t> answered;
  for (auto& f : late) {
    SubmitResult r = wait(std::move(f));
    ASSERT_TRUE(r.ok()) << "a write after the failed one was lost with it: " << r.text;
    answered.insert(r.message_id);
  }
  EXPECT_EQ(stored_ids(), answered);
  EXPECT_EQ(count("SELECT COUNT(*) FROM ballast"), 0);
  expect_serving_again_and_consistent(answered);
}

TEST_F(SubmitFaultTest, ADiskFillingUpMidBatchTellsTheSubmitsItTookThatTheDiskIsFull) {
  // As above, but the write inside the savepoint finds the disk full: the
  // Submits lost with its transaction are told so, not "unavailable".
  std::vector<std::future<SubmitResult>> early;
  std::future<void> ballast;
  {
    auto hold = hold_writer();
    FaultyVfs::instance().arm({VfsCall::kWrite, VfsFile::kWal, SQLITE_FULL, 0, false});
    early.push_back(submit(1));
    early.push_back(submit(2));
    ballast = writer_->submit([](store::Database& db) {
      db.exec("INSERT INTO ballast VALUES (randomblob(200000))");
    });
    hold->release();
  }
  ASSERT_EQ(ballast.wait_for(kPatience), std::future_status::ready);
  EXPECT_THROW(ballast.get(), store::StoreError);
  for (auto& f : early) {
    SubmitResult r = wait(std::move(f));
    EXPECT_EQ(r.error, Error::kStoreFull) << r.text;
    EXPECT_NE(r.text.find(path_), std::string::npos) << r.text;
    EXPECT_NE(r.text.find("the disk holding the store is full"), std::string::npos) << r.text;
  }
  EXPECT_TRUE(stored_ids().empty());
  EXPECT_TRUE(queued_ids().empty());
  expect_serving_again_and_consistent({});
}

TEST_F(SubmitFaultTest, AnEventThatFailsToCommitIsLoggedAndTheDaemonKeepsServing) {
  SubmitResult first = wait(submit(1));
  ASSERT_TRUE(first.ok()) << first.text;
  const uint64_t failed_before = writer_->stats().failed;
  {
    auto hold = hold_writer();
    FaultyVfs::instance().arm({VfsCall::kWrite, VfsFile::kWal, SQLITE_IOERR_WRITE, 0, true});
    // The core cancels the message: the queue forgets it at once and posts
    // the event (and the row's removal) to the writer, which fails.
    EXPECT_TRUE(core_->call([&] { return queues_->cancel(first.message_id, "test"); }));
    hold->release();
  }
  try {
    writer_->flush();  // returns once the event's batch is done, failed or not
  } catch (const store::StoreError&) {
  }
  EXPECT_GE(writer_->stats().failed, failed_before + 1);
  FaultyVfs::instance().disarm();
  // The store kept the row the queue forgot (logged as such): the message
  // comes back at the next start rather than being lost.
  EXPECT_EQ(stored_ids(), std::set<int64_t>{first.message_id});
  EXPECT_TRUE(queued_ids().empty());
  std::future<SubmitResult> future = submit(2);
  SubmitResult after = wait(std::move(future));
  ASSERT_TRUE(after.ok()) << after.text;
  EXPECT_TRUE(writer_->running());
  EXPECT_EQ(queued_ids(), std::set<int64_t>{after.message_id});
}

// The ACK's rule (queue/durable_receipts.h): a received message whose event
// failed to commit is not acknowledged, though the ACK's own commit, in a
// later batch, succeeds; once receipts are stored again, ACKs go out again.
TEST_F(SubmitFaultTest, NoAckForAReceiptWhoseEventFailedToCommitInAnEarlierBatch) {
  std::atomic<int> acks{0};
  AfterReceiptsDurable after_durable =
      durable_receipts(*journal_, [](Task then) { then(); });  // run on the writer thread: no core here
  auto receive = [&](int value) {
    auto message = codec_.new_message("qf.Status");
    EXPECT_TRUE(pb::TextFormat::ParseFromString("dest: 1 value: " + std::to_string(value), message.get()));
    return core_->call([&] { return queues_->receive(codec_.encode(*message), 2).size(); });
  };
  {
    auto hold = hold_writer();
    FaultyVfs::instance().arm({VfsCall::kWrite, VfsFile::kWal, SQLITE_IOERR_WRITE, 0, true});
    EXPECT_EQ(receive(1), 1u);
    hold->release();
  }
  try {
    writer_->flush();  // the received event's batch, failed
  } catch (const store::StoreError&) {
  }
  ASSERT_GE(FaultyVfs::instance().failures(), 1) << "the fault never hit";
  FaultyVfs::instance().disarm();
  after_durable([&acks] { ++acks; });
  writer_->flush();  // the ACK's own (empty) request: committed
  EXPECT_EQ(acks.load(), 0) << "acknowledged a message the store does not hold";
  EXPECT_TRUE(journal_->received_since(0).empty());

  EXPECT_EQ(receive(2), 1u);
  after_durable([&acks] { ++acks; });
  writer_->flush();
  EXPECT_EQ(acks.load(), 1) << "a stored receipt is acknowledged again";
  EXPECT_EQ(journal_->received_since(0).size(), 1u);
}

}  // namespace
}  // namespace acomms::queue
