// Durability of the queues across SIGKILL: a child process
// (queue_crash_child) submits from several threads as fast as it can, the
// way the daemon's Submit does, and prints each id once the submit
// returned; it is killed at a random moment, and the queue restored from the
// reopened store (WAL recovery) must hold every confirmed message, once,
// intact, and nothing the child did not attempt.
//
// SIGKILL loses the process, not the kernel's page cache, so this proves the
// commit protocol (nothing answered before COMMIT, WAL recovery, savepoints),
// not the fsync itself; synchronous=FULL is what covers a power loss.

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <google/protobuf/text_format.h>

#include <fstream>

#include "child_process.h"
#include "core/clock.h"
#include "queue/queue_manager.h"
#include "queue/sqlite_journal.h"
#include "queue_crash_protocol.h"
#include "store/group_commit_writer.h"
#include "store/store.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;
namespace crash = acomms::testing::queue_crash;
using crash::kRemoveEvery;

constexpr int kIterations = 30;
constexpr int kAppenders = 4;
constexpr uint32_t kSeed = 20261121;  // fixed: a failure replays the same kill times

// What the child confirmed on stdout before it died.
struct Confirmed {
  std::map<int64_t, std::pair<int, int64_t>> ok;  // id -> (thread, seq)
  std::map<std::pair<int, int64_t>, int64_t> id_of;
  std::set<int64_t> removed;
  std::map<int, int64_t> last_seq;  // thread -> highest confirmed seq
  bool ready = false;
  int64_t max_id = 0;
};

Confirmed parse(const std::string& out) {
  Confirmed confirmed;
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    // A last line without its newline was cut by the kill: not confirmed.
    if (lines.eof()) break;
    std::istringstream words(line);
    std::string what;
    words >> what;
    if (what == "ready") {
      confirmed.ready = true;
    } else if (what == "ok") {
      int64_t id = 0, seq = 0;
      int thread = 0;
      words >> id >> thread >> seq;
      confirmed.ok[id] = {thread, seq};
      confirmed.id_of[{thread, seq}] = id;
      auto [last, inserted] = confirmed.last_seq.emplace(thread, seq);
      if (!inserted) last->second = std::max(last->second, seq);
      confirmed.max_id = std::max(confirmed.max_id, id);
    } else if (what == "removed") {
      int64_t id = 0;
      words >> id;
      confirmed.removed.insert(id);
    } else {
      ADD_FAILURE() << "unexpected line from the child: " << line;
    }
  }
  return confirmed;
}

// Which (thread, seq) a restored message is; false if it is none the child makes.
bool identify(const dccl::Codec& codec, const QueuedMessage& m, int* thread, int64_t* seq) {
  auto message = codec.new_message(crash::kType);
  if (!message->ParseFromString(m.record.payload)) return false;
  const auto* type = message->GetDescriptor();
  const auto* reflection = message->GetReflection();
  *thread = reflection->GetInt32(*message, type->FindFieldByName("thread"));
  *seq = reflection->GetInt64(*message, type->FindFieldByName("seq"));
  // The encoding the queue will send must be the message's own.
  return reflection->GetString(*message, type->FindFieldByName("filler")) == std::string("\0\xff", 2) + "filler" &&
         m.encoded == codec.encode(*message);
}

class QueueCrashTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("acomms_queue_crash_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    proto_ = (root_ / "crash.proto").string();
    std::ofstream(proto_) << crash::kProto;
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(root_);
  }
  fs::path root_;
  std::string proto_;
};

TEST_F(QueueCrashTest, RestoredQueueHoldsEveryConfirmedSubmit) {
  std::mt19937 rng(kSeed);
  std::uniform_int_distribution<int> kill_after_ms(10, 300);
  int iterations_with_appends = 0;
  size_t total_confirmed = 0, total_removed = 0;

  for (int run = 0; run < kIterations; ++run) {
    SCOPED_TRACE("run " + std::to_string(run));
    std::string dir = (root_ / ("run" + std::to_string(run))).string();
    int delay = kill_after_ms(rng);
    SCOPED_TRACE("killed after " + std::to_string(delay) + " ms, data dir " + dir);

    Confirmed confirmed;
    {
      acomms::testing::ChildProcess child(QUEUE_CRASH_CHILD, {dir, std::to_string(kAppenders), proto_},
                                          dir + ".child");
      std::this_thread::sleep_for(std::chrono::milliseconds(delay));
      child.signal(SIGKILL);
      child.wait(std::chrono::seconds(10));
      // Anything but our SIGKILL (an exception, an abort) is a failure of its own.
      ASSERT_EQ(child.exit_signal(), SIGKILL) << "child stderr:\n" << child.stderr_text();
      confirmed = parse(child.stdout_text());
    }
    if (!confirmed.ok.empty()) ++iterations_with_appends;
    total_confirmed += confirmed.ok.size();
    total_removed += confirmed.removed.size();

    // Reopening must always work: WAL recovery, schema intact, quick_check ok.
    std::unique_ptr<store::Store> store;
    ASSERT_NO_THROW(store = std::make_unique<store::Store>(dir));
    store::GroupCommitWriter writer(store->db());
    SqliteJournal journal(writer);
    dccl::Codec codec;
    codec.load(proto_);
    v1::QueueConfig config;
    google::protobuf::TextFormat::ParseFromString(crash::kQueueConfig, &config);
    core::SystemClock clock;
    QueueManager queues(codec, config, 1, clock, journal);
    queues.restore();
    const Queue& restored = *queues.find_queue(crash::kType);

    // Everything restored is something the child attempted, exactly once,
    // with the id it was given. Restored is a SUBSET of attempted, not equal
    // to the printed set: a message can be committed and the child killed
    // before it printed the id. Such a message is the one in flight on its
    // thread: at most last printed seq + 1.
    std::set<std::pair<int, int64_t>> seen;
    std::set<int64_t> loaded_ids;
    for (const QueuedMessage& m : restored.messages()) {
      int thread = -1;
      int64_t seq = -1;
      ASSERT_TRUE(identify(codec, m, &thread, &seq)) << "message " << m.record.id << " was never attempted";
      EXPECT_EQ(m.in_flight_frame, 0u);
      EXPECT_TRUE(seen.insert({thread, seq}).second) << "t" << thread << "-" << seq << " twice";
      int64_t last = confirmed.last_seq.count(thread) ? confirmed.last_seq[thread] : -1;
      EXPECT_LE(seq, last + 1) << "t" << thread << "-" << seq << " was never attempted";
      auto printed = confirmed.id_of.find({thread, seq});
      if (printed != confirmed.id_of.end()) {
        EXPECT_EQ(m.record.id, printed->second);
      }
      EXPECT_FALSE(confirmed.removed.count(m.record.id)) << "message " << m.record.id << " removed, yet restored";
      loaded_ids.insert(m.record.id);
    }
    // Every confirmed append is there, unless its removal may have committed:
    // confirmed (printed) removals must be gone; a removal recorded but not
    // yet confirmed may go either way.
    for (const auto& [id, tag] : confirmed.ok) {
      bool removal_attempted = tag.second % kRemoveEvery == 0;
      if (removal_attempted) continue;
      EXPECT_TRUE(loaded_ids.count(id))
          << "confirmed message " << id << " (t" << tag.first << "-" << tag.second << ") lost";
    }
    // A confirmed removal's event is in the log, from the same transaction.
    int64_t dropped_events = writer
                                 .submit([](store::Database& db) {
                                   store::Statement q = db.prepare(
                                       "SELECT count(*) FROM event_log WHERE kind = 'dropped' AND detail = 'crash test'");
                                   q.step();
                                   return q.column_int64(0);
                                 })
                                 .get();
    EXPECT_GE(dropped_events, static_cast<int64_t>(confirmed.removed.size()));
    // Ids are never reused, not even across a crash.
    JournalMessage next;
    next.type = crash::kType;
    next.payload = "after";
    EXPECT_GT(journal.append(next), confirmed.max_id);
  }
  std::printf("queue crash: %d runs, %d with confirmed submits, %zu submits and %zu removals "
              "confirmed in all\n",
              kIterations, iterations_with_appends, total_confirmed, total_removed);
  // Most runs must get past start-up, or the test proves little.
  EXPECT_GE(iterations_with_appends, kIterations / 2);
}

// An ACK makes the sender forget its message: whatever the receiver
// acknowledged must be in its event log after a SIGKILL at any moment
// (queue/durable_receipts.h), or it is lost on both sides.
TEST_F(QueueCrashTest, EveryAcknowledgedReceiptSurvivesTheKill) {
  std::mt19937 rng(kSeed + 1);
  std::uniform_int_distribution<int> kill_after_ms(10, 300);
  size_t total_acked = 0;
  int runs_with_acks = 0;
  for (int run = 0; run < kIterations / 2; ++run) {
    std::string dir = (root_ / ("receive" + std::to_string(run))).string();
    int delay = kill_after_ms(rng);
    SCOPED_TRACE("run " + std::to_string(run) + ", killed after " + std::to_string(delay) + " ms, data dir " + dir);
    std::set<int64_t> acked;
    {
      acomms::testing::ChildProcess child(QUEUE_CRASH_CHILD, {dir, "receive", proto_}, dir + ".child");
      std::this_thread::sleep_for(std::chrono::milliseconds(delay));
      child.signal(SIGKILL);
      child.wait(std::chrono::seconds(10));
      ASSERT_EQ(child.exit_signal(), SIGKILL) << "child stderr:\n" << child.stderr_text();
      std::istringstream lines(child.stdout_text());
      std::string line;
      while (std::getline(lines, line)) {
        if (lines.eof()) break;  // cut by the kill: not confirmed
        std::istringstream words(line);
        std::string what;
        int64_t seq = -1;
        words >> what >> seq;
        if (what == "acked") acked.insert(seq);
      }
    }
    if (!acked.empty()) ++runs_with_acks;
    total_acked += acked.size();

    store::Store store(dir);
    store::GroupCommitWriter writer(store.db());
    SqliteJournal journal(writer);
    dccl::Codec codec;
    codec.load(proto_);
    std::set<int64_t> stored;
    for (const QueueEvent& event : journal.received_since(0)) {
      size_t used = 0;
      auto message = codec.decode_as(crash::kType, event.encoded, &used);
      stored.insert(message->GetReflection()->GetInt64(*message, message->GetDescriptor()->FindFieldByName("seq")));
    }
    for (int64_t seq : acked) EXPECT_TRUE(stored.count(seq)) << "message " << seq << " acknowledged, then lost";
  }
  std::printf("receive crash: %d runs, %d with ACKs, %zu ACKs in all\n", kIterations / 2, runs_with_acks, total_acked);
  EXPECT_GE(runs_with_acks, kIterations / 4);
}

}  // namespace
}  // namespace acomms::queue
