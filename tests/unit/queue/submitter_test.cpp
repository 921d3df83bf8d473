// Submitter::submit across its real threads: the caller's, the SQLite
// journal's group-commit writer and a running EventLoop as the core. The
// promises it keeps: the answer (the id) comes only once the message is
// committed and queued, and the queueing happens on the core thread; a
// refusal before storing (a message that does not encode, a full
// REFUSE_NEW queue) is answered at once and leaves no trace in the store;
// a store that stopped is answered UNAVAILABLE-style; every submit is
// answered exactly once.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "core/clock.h"
#include "core/event_loop.h"
#include "dccl/codec.h"
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
using Error = SubmitResult::Error;

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package qs;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional int32 dest = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 2 [(dccl.field) = { min: 0 max: 1000 }];
}
message Command {
  option (dccl.msg) = { codec_version: 4 id: 3 max_bytes: 16 };
  optional int32 dest = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 2 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

constexpr auto kPatience = 10s;  // a bound on waiting for an answer, never a sleep

// What the test sees of one submit's answer, and where it was given.
struct Answer {
  SubmitResult result;
  std::thread::id thread;
  int64_t stored_when_answered = -1;  // rows with the id, read by another connection at that moment
  size_t queued_when_answered = 0;    // the queue's size at that moment
};

class SubmitterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-submitter-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "qs.proto") << kProto;
    codec_.load((dir_ / "qs.proto").string());
    codec_.set_strict(true);  // as the daemon runs by default

    store_ = std::make_unique<store::Store>((dir_ / "data").string());
    writer_ = std::make_unique<store::GroupCommitWriter>(store_->db());
    journal_ = std::make_unique<SqliteJournal>(*writer_);
    v1::QueueConfig config;
    ASSERT_TRUE(pb::TextFormat::ParseFromString(
        R"(type { type: "qs.Status" roles { destination_field: "dest" } }
           type { type: "qs.Command" roles { destination_field: "dest" }
                  policy { max_queue: 1 on_full: REFUSE_NEW } })",
        &config));
    queues_ = std::make_unique<QueueManager>(codec_, config, 1, clock_, *journal_);
    core_ = std::make_unique<core::EventLoop>();
    submitter_ = std::make_unique<Submitter>(
        *queues_, [core = core_.get()](std::function<void()> work) { core->post(std::move(work)); });
    core_->start();
    core_thread_ = core_->call([] { return std::this_thread::get_id(); });
  }

  void TearDown() override {
    core_->stop();
    submitter_.reset();
    queues_.reset();
    writer_->stop();
    journal_.reset();
    writer_.reset();
    store_.reset();
    fs::remove_all(dir_);
  }

  std::unique_ptr<pb::Message> message(const std::string& type, const std::string& text) {
    auto m = codec_.new_message(type);
    EXPECT_TRUE(pb::TextFormat::ParseFromString(text, m.get())) << text;
    return m;
  }

  // Submits and returns the answer's future. At the moment of the answer it
  // notes the thread, whether the message is in the store (a separate
  // read-only connection sees only committed rows) and the queue's size.
  std::future<Answer> submit(const std::string& type, const std::string& text) {
    auto promise = std::make_shared<std::promise<Answer>>();
    auto answers = std::make_shared<std::atomic<int>>(0);
    std::future<Answer> future = promise->get_future();
    submitter_->submit(*message(type, text), 0, [=, this](SubmitResult result) {
      if (answers->fetch_add(1) > 0) {
        ADD_FAILURE() << "answered twice";
        return;
      }
      Answer answer;
      answer.thread = std::this_thread::get_id();
      if (result.ok()) {
        answer.stored_when_answered = rows("SELECT COUNT(*) FROM queued_messages WHERE id = " +
                                           std::to_string(result.message_id));
        // The answer for a queued message is given on the core thread.
        answer.queued_when_answered = queues_->find_queue(type)->size();
      }
      answer.result = std::move(result);
      promise->set_value(std::move(answer));
    });
    return future;
  }

  Answer wait(std::future<Answer> future) {
    if (future.wait_for(kPatience) != std::future_status::ready) {
      ADD_FAILURE() << "no answer within " << kPatience.count() << " s";
      return {};
    }
    return future.get();
  }

  // One number from the store, read through a connection of its own.
  int64_t rows(const std::string& sql) {
    store::Database reader(store_->db().path(), store::Database::Mode::kReadOnly);
    store::Statement query = reader.prepare(sql);
    query.step();
    return query.column_int64(0);
  }

  fs::path dir_;
  dccl::Codec codec_;
  core::SimulatedClock clock_{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
  std::unique_ptr<store::Store> store_;
  std::unique_ptr<store::GroupCommitWriter> writer_;
  std::unique_ptr<SqliteJournal> journal_;
  std::unique_ptr<QueueManager> queues_;
  std::unique_ptr<core::EventLoop> core_;
  std::unique_ptr<Submitter> submitter_;
  std::thread::id core_thread_;
};

TEST_F(SubmitterTest, AnswersTheIdOnTheCoreThreadOnceTheMessageIsCommittedAndQueued) {
  Answer answer = wait(submit("qs.Status", "dest: 2 value: 7"));
  ASSERT_TRUE(answer.result.ok()) << answer.result.text;
  EXPECT_GT(answer.result.message_id, 0);
  EXPECT_EQ(answer.thread, core_thread_) << "accept ran off the core thread";
  EXPECT_EQ(answer.stored_when_answered, 1) << "answered before the commit";
  EXPECT_EQ(answer.queued_when_answered, 1u) << "answered before the message was queued";
  int64_t id = answer.result.message_id;
  EXPECT_EQ(core_->call([&] { return queues_->find_queue("qs.Status")->messages().front().record.id; }), id);

  // Submits from several threads at once: each answered once, with its own id.
  constexpr int kThreads = 4;
  std::vector<std::future<Answer>> futures(kThreads);
  std::vector<std::thread> clients;
  for (int i = 0; i < kThreads; ++i) {
    clients.emplace_back([&, i] { futures[i] = submit("qs.Status", "value: " + std::to_string(i)); });
  }
  for (auto& client : clients) client.join();
  std::set<int64_t> ids{id};
  for (auto& future : futures) {
    Answer a = wait(std::move(future));
    EXPECT_TRUE(a.result.ok()) << a.result.text;
    EXPECT_EQ(a.thread, core_thread_);
    ids.insert(a.result.message_id);
  }
  EXPECT_EQ(ids.size(), 1u + kThreads);
  EXPECT_EQ(core_->call([&] { return queues_->find_queue("qs.Status")->size(); }), 1u + kThreads);
}

TEST_F(SubmitterTest, AMessageThatDoesNotEncodeIsAnsweredAtOnceAndNothingIsStored) {
  std::future<Answer> future = submit("qs.Status", "value: 5000");
  // Answered on this thread, before submit() returned.
  ASSERT_EQ(future.wait_for(0s), std::future_status::ready);
  Answer answer = future.get();
  EXPECT_EQ(answer.thread, std::this_thread::get_id());
  EXPECT_EQ(answer.result.error, Error::kInvalidMessage);
  EXPECT_NE(answer.result.text.find("value"), std::string::npos) << answer.result.text;
  EXPECT_EQ(answer.result.message_id, 0);
  writer_->flush();
  EXPECT_EQ(rows("SELECT COUNT(*) FROM queued_messages"), 0);
  EXPECT_EQ(rows("SELECT COUNT(*) FROM event_log"), 0);
  EXPECT_EQ(core_->call([&] { return queues_->find_queue("qs.Status")->size(); }), 0u);
}

TEST_F(SubmitterTest, AFullRefuseNewQueueRefusesBeforeStoring) {
  ASSERT_TRUE(wait(submit("qs.Command", "value: 1")).result.ok());
  writer_->flush();
  const int64_t events = rows("SELECT COUNT(*) FROM event_log");

  std::future<Answer> future = submit("qs.Command", "value: 2");
  ASSERT_EQ(future.wait_for(0s), std::future_status::ready) << "waited for the store to refuse";
  Answer answer = future.get();
  EXPECT_EQ(answer.result.error, Error::kQueueFull);
  EXPECT_EQ(answer.result.text, "queue qs.Command is full (max_queue 1) and refuses new messages");
  writer_->flush();
  EXPECT_EQ(rows("SELECT COUNT(*) FROM queued_messages"), 1);
  EXPECT_EQ(rows("SELECT COUNT(*) FROM event_log"), events);
  EXPECT_EQ(core_->call([&] { return queues_->stats("qs.Command").refused; }), 1u);
}

TEST_F(SubmitterTest, AnUnknownTypeIsAnsweredAtOnce) {
  dccl::Codec other;
  std::ofstream(dir_ / "other.proto") << R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package other;
message Ping {
  option (dccl.msg) = { codec_version: 4 id: 9 max_bytes: 8 };
  optional int32 value = 1 [(dccl.field) = { min: 0 max: 10 }];
})";
  other.load((dir_ / "other.proto").string());
  auto ping = other.new_message("other.Ping");
  std::optional<SubmitResult> answer;
  submitter_->submit(*ping, 0, [&](SubmitResult result) { answer = std::move(result); });
  ASSERT_TRUE(answer);
  EXPECT_EQ(answer->error, Error::kUnknownType);
  EXPECT_EQ(answer->text, "no DCCL type other.Ping is loaded");
}

TEST_F(SubmitterTest, AStoppedStoreIsAnsweredAsTheStoreAndNothingIsQueued) {
  writer_->stop();
  std::future<Answer> future = submit("qs.Status", "value: 1");
  ASSERT_EQ(future.wait_for(0s), std::future_status::ready);
  Answer answer = future.get();
  EXPECT_EQ(answer.result.error, Error::kStoreUnavailable);
  EXPECT_EQ(answer.result.text.rfind("store: ", 0), 0u) << answer.result.text;
  EXPECT_EQ(core_->call([&] { return queues_->find_queue("qs.Status")->size(); }), 0u);
}

}  // namespace
}  // namespace acomms::queue
