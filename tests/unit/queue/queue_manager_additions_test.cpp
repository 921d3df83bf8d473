// QueueManager additions on the simulated clock: retransmissions recognised
// on receive (queue.duplicate_window_s), Flush, and add_types after the
// codec loaded more definitions.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>

#include "queue_manager_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package qa;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
message Command {
  option (dccl.msg) = { codec_version: 4 id: 3 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

constexpr const char* kMoreProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package qb;
message Extra {
  option (dccl.msg) = { codec_version: 4 id: 20 max_bytes: 16 };
  optional int32 dest = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 2 [(dccl.field) = { min: 0 max: 1000 }];
}
message Other {
  option (dccl.msg) = { codec_version: 4 id: 21 max_bytes: 16 };
  optional int32 dest = 1 [(dccl.field) = { min: 0 max: 30 }];
}
message NoId {
  option (dccl.msg) = { codec_version: 4 omit_id: true max_bytes: 16 };
  optional int32 value = 1 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

using testing::kOwnId;

class QueueAdditionsTest : public testing::QueueManagerFixture {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("acomms-queue-add-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::ofstream(dir_ / "qa.proto") << kProto;
    std::ofstream(dir_ / "qb.proto") << kMoreProto;
    codec_.load((dir_ / "qa.proto").string());
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Status and Command get src/dest roles; `text` is extra QueueConfig.
  QueueManager& make(const std::string& text = "") {
    v1::QueueConfig config;
    EXPECT_TRUE(pb::TextFormat::ParseFromString(text, &config)) << text;
    for (const char* type : {"qa.Status", "qa.Command"}) {
      auto* entry = config.add_type();
      entry->set_type(type);
      entry->mutable_roles()->set_source_field("src");
      entry->mutable_roles()->set_destination_field("dest");
    }
    return install(std::make_unique<QueueManager>(codec_, config, kOwnId, clock_, journal_));
  }

  std::vector<std::string> queue_names() {
    std::vector<std::string> names;
    for (const Queue* q : manager_->queues()) names.push_back(q->type());
    std::sort(names.begin(), names.end());
    return names;
  }

};

// ------------------------------------------------------------ duplicates

TEST_F(QueueAdditionsTest, SameFrameTwiceIsDeliveredOnceAndCounted) {
  make();
  std::string frame = encode("qa.Status", "dest: 1 value: 7") + encode("qa.Command", "dest: 0 value: 8");
  auto first = manager_->receive(frame, 4);
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0].src, 4);
  EXPECT_EQ(manager_->duplicates(), 0u);
  at(30);
  auto again = manager_->receive(frame, 4);
  EXPECT_TRUE(again.empty()) << "a retransmission was passed on again";
  EXPECT_EQ(manager_->duplicates(), 2u);
  EXPECT_EQ(manager_->stats("qa.Status").received, 1u);
  EXPECT_EQ(manager_->stats("qa.Command").received, 1u);
  EXPECT_EQ(count(QueueEventKind::kReceived), 2);
  EXPECT_EQ(manager_->malformed_frames(), 0u);
}

TEST_F(QueueAdditionsTest, OneRetransmittedMessageAmongNewOnesIsTheOnlyOneHeldBack) {
  make();
  std::string old_one = encode("qa.Status", "dest: 1 value: 1");
  ASSERT_EQ(manager_->receive(old_one, 4).size(), 1u);
  auto mixed = manager_->receive(encode("qa.Status", "dest: 1 value: 2") + old_one +
                                     encode("qa.Status", "dest: 1 value: 3"),
                                 4);
  ASSERT_EQ(mixed.size(), 2u) << "messages after the duplicate in the frame were lost";
  EXPECT_EQ(mixed[0].encoded, encode("qa.Status", "dest: 1 value: 2"));
  EXPECT_EQ(mixed[1].encoded, encode("qa.Status", "dest: 1 value: 3"));
  EXPECT_EQ(manager_->duplicates(), 1u);
}

TEST_F(QueueAdditionsTest, SameBytesFromAnotherSourceAreNotDuplicates) {
  make();
  std::string frame = encode("qa.Status", "dest: 1 value: 7");  // no src field: the transmission's
  ASSERT_EQ(manager_->receive(frame, 4).size(), 1u);
  auto other = manager_->receive(frame, 5);
  ASSERT_EQ(other.size(), 1u);
  EXPECT_EQ(other[0].src, 5);
  EXPECT_EQ(manager_->duplicates(), 0u);
  // With a source field the message's own source counts, whoever relayed it.
  std::string sourced = encode("qa.Status", "src: 9 dest: 1 value: 7");
  ASSERT_EQ(manager_->receive(sourced, 4).size(), 1u);
  EXPECT_TRUE(manager_->receive(sourced, 6).empty());
  EXPECT_EQ(manager_->duplicates(), 1u);
}

// (The window is never shorter than the type's ttl: delivered_once_test.cpp.)
TEST_F(QueueAdditionsTest, AfterTheConfiguredWindowTheSameFrameIsDeliveredAgain) {
  make("duplicate_window_s: 10 defaults { ttl_s: 5 }");
  std::string frame = encode("qa.Status", "dest: 1 value: 7");
  ASSERT_EQ(manager_->receive(frame, 4).size(), 1u);
  at(9);
  EXPECT_TRUE(manager_->receive(frame, 4).empty());
  at(11);
  EXPECT_EQ(manager_->receive(frame, 4).size(), 1u);
  EXPECT_EQ(manager_->duplicates(), 1u);
}

TEST_F(QueueAdditionsTest, DefaultWindowIsFiveMinutesForATypeWithAShorterTtl) {
  make("defaults { ttl_s: 120 }");
  std::string frame = encode("qa.Status", "dest: 1 value: 7");
  ASSERT_EQ(manager_->receive(frame, 4).size(), 1u);
  at(299);
  EXPECT_TRUE(manager_->receive(frame, 4).empty());
  at(299 + 301);
  EXPECT_EQ(manager_->receive(frame, 4).size(), 1u);
}

// A command whose ACK was lost while this node restarted is sent again: the
// restarted node must not pass it on a second time.
TEST_F(QueueAdditionsTest, AfterARestartWhatWasReceivedWithinTheWindowIsStillADuplicate) {
  make("duplicate_window_s: 60 defaults { ttl_s: 60 }");
  std::string command = encode("qa.Command", "dest: 1 value: 8");
  ASSERT_EQ(manager_->receive(command, 4).size(), 1u);
  at(20);
  make("duplicate_window_s: 60 defaults { ttl_s: 60 }");  // the restarted process: same journal, empty memory
  manager_->restore();
  EXPECT_TRUE(manager_->receive(command, 4).empty()) << "the resent command was passed on twice";
  EXPECT_EQ(manager_->duplicates(), 1u);
  EXPECT_EQ(manager_->receive(encode("qa.Command", "dest: 1 value: 9"), 4).size(), 1u);
  at(61);
  EXPECT_EQ(manager_->receive(command, 4).size(), 1u) << "its window ended 60 s after it was received";
}

TEST_F(QueueAdditionsTest, WindowZeroDeliversEveryCopy) {
  make("duplicate_window_s: 0");
  std::string frame = encode("qa.Status", "dest: 1 value: 7");
  for (int i = 0; i < 3; ++i) EXPECT_EQ(manager_->receive(frame, 4).size(), 1u);
  EXPECT_EQ(manager_->duplicates(), 0u);
}

TEST_F(QueueAdditionsTest, MessagesForOtherNodesAreNotRememberedAsSeen) {
  make();
  std::string for_nine = encode("qa.Status", "dest: 9 value: 7");
  EXPECT_TRUE(manager_->receive(for_nine, 4).empty());
  EXPECT_TRUE(manager_->receive(for_nine, 4).empty());
  EXPECT_EQ(manager_->duplicates(), 0u) << "a message not for us counted as a duplicate";
}

TEST_F(QueueAdditionsTest, NegativeOrNonFiniteWindowIsRefused) {
  v1::QueueConfig config;
  for (double bad : {-1.0, -0.001, std::numeric_limits<double>::infinity(), std::nan("")}) {
    config.set_duplicate_window_s(bad);
    EXPECT_THROW(QueueManager(codec_, config, kOwnId, clock_, journal_), std::invalid_argument) << bad;
  }
  config.set_duplicate_window_s(0);
  EXPECT_NO_THROW(QueueManager(codec_, config, kOwnId, clock_, journal_));
  config.set_duplicate_window_s(0.5);
  EXPECT_NO_THROW(QueueManager(codec_, config, kOwnId, clock_, journal_));
}

// ------------------------------------------------------------ flush

TEST_F(QueueAdditionsTest, FlushRemovesEveryMessageOfTheTypeWithDroppedEvents) {
  make();
  std::vector<int64_t> ids;
  for (int i = 0; i < 3; ++i) ids.push_back(submit("qa.Status", "dest: 2 value: " + std::to_string(i)));
  int64_t command = submit("qa.Command", "dest: 2 value: 9");
  size_t events_before = journal_.events().size();

  EXPECT_EQ(manager_->flush("qa.Status", "flushed by operator"), 3u);
  EXPECT_EQ(manager_->find_queue("qa.Status")->size(), 0u);
  ASSERT_EQ(manager_->find_queue("qa.Command")->size(), 1u);
  EXPECT_EQ(manager_->find_queue("qa.Command")->messages().front().record.id, command);
  EXPECT_EQ(manager_->stats("qa.Status").dropped, 3u);
  EXPECT_EQ(manager_->stats("qa.Command").dropped, 0u);
  EXPECT_EQ(journal_.stored(), 1u) << "flushed messages are still in the journal";

  std::vector<int64_t> dropped;
  const std::vector<QueueEvent> events = journal_.events();
  for (size_t i = events_before; i < events.size(); ++i) {
    const QueueEvent& e = events[i];
    EXPECT_EQ(e.kind, QueueEventKind::kDropped);
    EXPECT_EQ(e.type, "qa.Status");
    EXPECT_EQ(e.detail, "flushed by operator");
    EXPECT_TRUE(e.removes_message);
    dropped.push_back(e.message_id);
  }
  std::sort(dropped.begin(), dropped.end());
  EXPECT_EQ(dropped, ids);

  EXPECT_EQ(manager_->flush("qa.Status", "again"), 0u) << "an empty queue flushes nothing";
}

TEST_F(QueueAdditionsTest, FlushTakesMessagesInFlightAndTheirAckChangesNothing) {
  make();
  submit("qa.Status", "dest: 2 value: 1");
  submit("qa.Status", "dest: 2 value: 2");
  at(10);
  auto frames = manager_->build_frames(DataRequest{kAnyDestination, 100, 1, true});
  ASSERT_EQ(frames.size(), 1u);
  ASSERT_EQ(manager_->find_queue("qa.Status")->in_flight(), 2u);
  submit("qa.Status", "dest: 2 value: 3");
  EXPECT_EQ(manager_->flush("qa.Status", "flush"), 3u);
  EXPECT_EQ(manager_->find_queue("qa.Status")->in_flight(), 0u);
  manager_->on_ack(frames[0].frame_id);
  EXPECT_EQ(manager_->stats("qa.Status").acked, 0u);
  at(20);
  EXPECT_TRUE(manager_->build_frames(DataRequest{kAnyDestination, 100, 1, true}).empty());
  EXPECT_EQ(manager_->stats("qa.Status").retried, 0u) << "a flushed message came back as a retry";
  EXPECT_EQ(journal_.stored(), 0u);
}

TEST_F(QueueAdditionsTest, FlushOfAnUnknownTypeThrowsUnknownTypeError) {
  make();
  EXPECT_THROW(manager_->flush("qa.Nope", "x"), UnknownTypeError);
  codec_.load((dir_ / "qb.proto").string());
  // Loaded in the codec but without a queue yet: still unknown to the queues.
  EXPECT_THROW(manager_->flush("qb.Extra", "x"), UnknownTypeError);
}

// ------------------------------------------------------------ add_types

TEST_F(QueueAdditionsTest, AddTypesMakesQueuesForOnlyTheNewlyLoadedTypes) {
  make();
  int64_t kept = submit("qa.Status", "dest: 2 value: 1");
  EXPECT_EQ(queue_names(), (std::vector<std::string>{"qa.Command", "qa.Status"}));
  EXPECT_TRUE(manager_->add_types().empty()) << "nothing new loaded";

  codec_.load((dir_ / "qb.proto").string());
  std::vector<std::string> added = manager_->add_types();
  std::sort(added.begin(), added.end());
  EXPECT_EQ(added, (std::vector<std::string>{"qb.Extra", "qb.Other"})) << "omit_id types cannot be queued";
  EXPECT_EQ(queue_names(), (std::vector<std::string>{"qa.Command", "qa.Status", "qb.Extra", "qb.Other"}));
  EXPECT_EQ(manager_->find_queue("qb.NoId"), nullptr);
  // Existing queues keep their messages.
  ASSERT_EQ(manager_->find_queue("qa.Status")->size(), 1u);
  EXPECT_EQ(manager_->find_queue("qa.Status")->messages().front().record.id, kept);
  EXPECT_TRUE(manager_->add_types().empty()) << "the second call added again";

  // The new queues work: submit, send, receive.
  submit("qb.Extra", "dest: 2 value: 5");
  EXPECT_EQ(manager_->find_queue("qb.Extra")->size(), 1u);
  auto received = manager_->receive(encode("qb.Extra", "dest: 1 value: 6"), 3);
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(received[0].type, "qb.Extra");
}

TEST_F(QueueAdditionsTest, AddedTypesTakeTheirConfiguredPolicyAndTheDefaults) {
  // The config may name types that are loaded (the constructor checks); a
  // type added later gets the defaults.
  make("defaults { ttl_s: 77 max_queue: 5 }");
  codec_.load((dir_ / "qb.proto").string());
  manager_->add_types();
  ASSERT_NE(manager_->find_queue("qb.Extra"), nullptr);
  EXPECT_DOUBLE_EQ(manager_->find_queue("qb.Extra")->policy().ttl_s, 77);
  EXPECT_EQ(manager_->find_queue("qb.Extra")->policy().max_queue, 5u);
}


// The Submit path that does not wait for the disk: the checks and encoding
// happen on the caller's thread (errors answered there, nothing journaled),
// the answer is the message's id once it is journaled and queued.
TEST_F(QueueAdditionsTest, SubmitFillsTheRolesAndAnswersWithTheIdOnceQueued) {
  make();
  SubmitResult result = submit_result("qa.Status", "dest: 3 value: 7", 12);
  ASSERT_TRUE(result.ok()) << result.text;
  EXPECT_GT(result.message_id, 0);
  EXPECT_EQ(journal_.stored(), 1u);
  ASSERT_EQ(manager_->find_queue("qa.Status")->size(), 1u);
  const QueuedMessage& queued = manager_->find_queue("qa.Status")->messages().front();
  EXPECT_EQ(queued.record.id, result.message_id);
  EXPECT_EQ(queued.record.src, kOwnId);  // source role filled
  EXPECT_EQ(queued.record.dest, 3);
  EXPECT_EQ(queued.record.ttl_s, 12);
  EXPECT_EQ(queued.encoded, encode("qa.Status", "src: 1 dest: 3 value: 7"));
  EXPECT_EQ(journal_.load().front().id, result.message_id);

  codec_.set_strict(true);  // as the daemon runs by default
  SubmitResult bad = submit_result("qa.Status", "value: 5000");
  EXPECT_EQ(bad.error, SubmitResult::Error::kInvalidMessage);
  EXPECT_NE(bad.text.find("value"), std::string::npos) << bad.text;
  EXPECT_EQ(bad.message_id, 0);
  EXPECT_EQ(journal_.stored(), 1u);
  EXPECT_EQ(manager_->find_queue("qa.Status")->size(), 1u);
  EXPECT_GT(submit("qa.Status", "value: 1"), result.message_id);
}

// MemoryJournal completes inside the submit; what the answer itself throws
// there belongs to its caller and must not come back as a second answer.
TEST_F(QueueAdditionsTest, SubmitAnswersOnceEvenWhenTheAnswerThrows) {
  make();
  int answers = 0;
  EXPECT_THROW(submitter_->submit(*message("qa.Status", "value: 1"), 0,
                                  [&answers](const SubmitResult& result) {
                                    ++answers;
                                    EXPECT_TRUE(result.ok()) << result.text;
                                    throw std::runtime_error("the client went away");
                                  }),
               std::runtime_error);
  EXPECT_EQ(answers, 1);
  EXPECT_EQ(manager_->find_queue("qa.Status")->size(), 1u);
}

}  // namespace
}  // namespace acomms::queue
