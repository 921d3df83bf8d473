// The queues on the simulated clock: the priority contest and its ties,
// blackout, ttl expiry, newest_first, max_queue overflow, destination rules,
// stitching byte-exact against DCCL encodings, acks, retries, unstitching,
// roles, and restoring from the journal.

#include "queue/queue_manager.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/event_loop.h"
#include "core/logging.h"
#include "dccl/hex.h"
#include "queue_manager_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;
using namespace std::chrono_literals;

// Three types with the same shape: 1-byte id + 27 bits body = 5 bytes each.
constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package qt;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
  optional double time = 4 [(dccl.field) = { min: 0 max: 2000000000 precision: 0 }];
}
message Command {
  option (dccl.msg) = { codec_version: 4 id: 3 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
  optional double time = 4 [(dccl.field) = { min: 0 max: 2000000000 precision: 0 }];
}
message Ctd {
  option (dccl.msg) = { codec_version: 4 id: 4 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
  optional double time = 4 [(dccl.field) = { min: 0 max: 2000000000 precision: 0 }];
}
)";

using testing::kOwnId;
using testing::kStart;

class QueueTest : public testing::QueueManagerFixture {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-queue-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "qt.proto") << kProto;
    codec_.load((dir_ / "qt.proto").string());
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Builds the manager from a QueueConfig in text format. Every type gets
  // the src/dest/time roles unless the text configures it.
  QueueManager& make(const std::string& config_text = "") {
    v1::QueueConfig config;
    EXPECT_TRUE(pb::TextFormat::ParseFromString(config_text, &config));
    for (const char* type : {"qt.Status", "qt.Command", "qt.Ctd"}) {
      bool listed = false;
      for (auto& entry : *config.mutable_type()) listed = listed || entry.type() == type;
      if (!listed) config.add_type()->set_type(type);
    }
    for (auto& entry : *config.mutable_type()) {
      if (!entry.has_roles()) {
        entry.mutable_roles()->set_source_field("src");
        entry.mutable_roles()->set_destination_field("dest");
        entry.mutable_roles()->set_timestamp_field("time");
      }
    }
    return install(std::make_unique<QueueManager>(codec_, config, kOwnId, clock_, journal_));
  }

  // Frames for one transmission; every test frame fits `room` bytes.
  std::vector<Frame> request(uint32_t room, uint32_t frames = 1, int32_t dest = kAnyDestination,
                             bool ack = true) {
    return manager_->build_frames(DataRequest{dest, room, frames, ack});
  }

  // Encoded size of one test message (all three types have the same shape).
  uint32_t one() {
    return static_cast<uint32_t>(codec_.encode(*message("qt.Status", "src: 1 dest: 2 value: 1 time: 1")).size());
  }

  // Types in the first frame of a transmission with room for `n` messages.
  std::vector<std::string> sent_types(uint32_t n = 1) {
    auto frames = request(n * one());
    if (frames.empty()) return {"<no frame>"};
    return types_in(frames[0]);
  }

  std::vector<std::string> types_in(const Frame& frame) {
    std::vector<std::string> types;
    for (const auto& m : codec_.decode(frame.bytes)) types.push_back(m->GetDescriptor()->full_name());
    return types;
  }
};

TEST_F(QueueTest, HigherValueBaseWinsThenTheOtherQueueCatchesUp) {
  make(R"(type { type: "qt.Status" policy { value_base: 1 ttl_s: 100 } }
          type { type: "qt.Command" policy { value_base: 2 ttl_s: 100 } })");
  for (int i = 0; i < 3; ++i) {
    submit("qt.Status", "dest: 2 value: 1");
    submit("qt.Command", "dest: 2 value: 2");
  }
  at(10);  // P: Status 0.1, Command 0.2
  EXPECT_EQ(sent_types(), std::vector<std::string>{"qt.Command"});
  at(15);  // Status 0.15, Command (just sent) 2 * 5 / 100 = 0.1
  EXPECT_EQ(sent_types(), std::vector<std::string>{"qt.Status"});
  at(25);  // Status 0.1, Command 2 * 15 / 100 = 0.3
  EXPECT_EQ(sent_types(), std::vector<std::string>{"qt.Command"});
}

TEST_F(QueueTest, TieGoesToTheQueueThatSentLongestAgo) {
  make(R"(type { type: "qt.Status" policy { value_base: 1 ttl_s: 100 } }
          type { type: "qt.Command" policy { value_base: 2 ttl_s: 100 } })");
  at(10);
  submit("qt.Status", "dest: 2 value: 1");
  EXPECT_EQ(sent_types(), std::vector<std::string>{"qt.Status"});  // Status sends at 10
  at(20);
  submit("qt.Command", "dest: 2 value: 2");
  EXPECT_EQ(sent_types(), std::vector<std::string>{"qt.Command"});  // Command sends at 20
  manager_->on_ack(0);  // no such frame: harmless
  submit("qt.Status", "dest: 2 value: 3");
  submit("qt.Command", "dest: 2 value: 4");
  at(30);  // Status 1 * 20 / 100 = 0.2 == Command 2 * 10 / 100 = 0.2
  EXPECT_EQ(sent_types(), std::vector<std::string>{"qt.Status"});
}

TEST_F(QueueTest, FullTieGoesToTheLowerDcclId) {
  make();
  submit("qt.Ctd", "dest: 2 value: 1");
  submit("qt.Command", "dest: 2 value: 2");
  at(10);  // both created at start, never sent: equal P, equal last-sent
  EXPECT_EQ(sent_types(), std::vector<std::string>{"qt.Command"});
}

TEST_F(QueueTest, BlackoutKeepsAQueueOutOfTheContest) {
  make(R"(type { type: "qt.Command" policy { value_base: 10 blackout_time_s: 60 } })");
  for (int i = 0; i < 3; ++i) {
    submit("qt.Command", "dest: 2 value: 1");
    submit("qt.Status", "dest: 2 value: 2");
  }
  at(10);
  EXPECT_EQ(sent_types(), std::vector<std::string>{"qt.Command"});
  at(50);  // Command would win on priority but is in blackout until 70
  EXPECT_EQ(sent_types(), std::vector<std::string>{"qt.Status"});
  at(71);
  EXPECT_EQ(sent_types(), std::vector<std::string>{"qt.Command"});
}

TEST_F(QueueTest, MessagesPastTtlExpireAndAreNeverSent) {
  make(R"(type { type: "qt.Status" policy { ttl_s: 10 } })");
  int64_t old_id = submit("qt.Status", "dest: 2 value: 1");
  at(5);
  int64_t short_id = submit("qt.Status", "dest: 2 value: 2", /*ttl_s=*/2);
  at(8);  // the per-message ttl of 2 s has passed for the second
  manager_->expire();
  EXPECT_EQ(manager_->find_queue("qt.Status")->size(), 1u);
  at(11);
  EXPECT_TRUE(request(100).empty());
  EXPECT_EQ(manager_->stats("qt.Status").expired, 2u);
  EXPECT_EQ(journal_.stored(), 0u);
  std::vector<int64_t> expired;
  for (const auto& e : journal_.events()) {
    if (e.kind == QueueEventKind::kExpired) {
      expired.push_back(e.message_id);
      EXPECT_TRUE(e.removes_message);
    }
  }
  EXPECT_EQ(expired, (std::vector<int64_t>{short_id, old_id}));
}

TEST_F(QueueTest, NewestFirstOrOldestFirst) {
  make(R"(type { type: "qt.Status" policy { newest_first: true } }
          type { type: "qt.Command" policy { newest_first: false } })");
  for (int v = 1; v <= 3; ++v) {
    submit("qt.Status", "dest: 2 value: " + std::to_string(v));
    submit("qt.Command", "dest: 2 value: " + std::to_string(v));
  }
  at(10);
  auto frames = request(2 * one());
  ASSERT_EQ(frames.size(), 1u);
  auto decoded = codec_.decode(frames[0].bytes);
  ASSERT_EQ(decoded.size(), 2u);
  for (const auto& m : decoded) {
    std::string text = m->ShortDebugString();
    if (m->GetDescriptor()->name() == "Status") {
      EXPECT_NE(text.find("value: 3"), std::string::npos) << text;
    } else {
      EXPECT_NE(text.find("value: 1"), std::string::npos) << text;
    }
  }
}

TEST_F(QueueTest, FullQueueDropsTheOldestOrRefusesTheNew) {
  make(R"(type { type: "qt.Status" policy { max_queue: 2 } }
          type { type: "qt.Command" policy { max_queue: 2 on_full: REFUSE_NEW } })");
  int64_t first = submit("qt.Status", "value: 1");
  submit("qt.Status", "value: 2");
  submit("qt.Status", "value: 3");
  const Queue* status = manager_->find_queue("qt.Status");
  ASSERT_EQ(status->size(), 2u);
  EXPECT_NE(status->messages().front().record.id, first);
  EXPECT_EQ(manager_->stats("qt.Status").dropped, 1u);

  int64_t command = submit("qt.Command", "value: 1");
  // Both stored while the queue still had room; it fills before the third
  // is accepted (concurrent Submits): that one is stored, then refused.
  hold_core();
  Answer second = submit_async("qt.Command", "value: 2");
  Answer third = submit_async("qt.Command", "value: 3");
  EXPECT_FALSE(second->has_value() || third->has_value()) << "answered before the core queued them";
  int64_t refused = journal_.events().back().message_id;  // the third's "queued", as it was stored
  run_core();
  ASSERT_TRUE(second->has_value() && third->has_value());
  EXPECT_TRUE((*second)->ok());
  EXPECT_EQ((*third)->error, SubmitResult::Error::kQueueFull);
  EXPECT_EQ((*third)->text, "queue qt.Command is full (max_queue 2) and refuses new messages");
  EXPECT_EQ(manager_->find_queue("qt.Command")->size(), 2u);
  bool logged = false;
  for (const auto& e : journal_.events()) {
    if (e.kind == QueueEventKind::kDropped && e.message_id == refused) {
      logged = true;
      EXPECT_EQ(e.detail, "queue full: new message refused");
      EXPECT_TRUE(e.removes_message);
    }
  }
  EXPECT_TRUE(logged);
  EXPECT_EQ(journal_.stored(), 4u);  // neither the dropped nor the refused one is kept
  EXPECT_EQ(manager_->stats("qt.Command").dropped, 1u);

  // Once the queue is full, a Submit is refused before it is stored: no id,
  // no event, nothing written.
  const size_t events = journal_.events().size();
  SubmitResult full = submit_result("qt.Command", "value: 4");
  EXPECT_EQ(full.error, SubmitResult::Error::kQueueFull) << "a full REFUSE_NEW queue took a new message";
  EXPECT_EQ(full.text, "queue qt.Command is full (max_queue 2) and refuses new messages");
  EXPECT_EQ(full.message_id, 0);
  EXPECT_EQ(journal_.events().size(), events);
  EXPECT_EQ(journal_.stored(), 4u);
  EXPECT_EQ(manager_->stats("qt.Command").refused, 1u);
  EXPECT_EQ(manager_->stats("qt.Command").dropped, 1u);
  // DROP_OLDEST never refuses.
  EXPECT_EQ(manager_->stats("qt.Status").refused, 0u);
  submit("qt.Status", "value: 4");

  // With room again, new messages are taken.
  ASSERT_TRUE(manager_->cancel(command, "test"));
  submit("qt.Command", "value: 5");
  EXPECT_EQ(manager_->find_queue("qt.Command")->size(), 2u);
}

// The refusal before storing must end as soon as a message leaves the
// queue, whichever way it leaves.
TEST_F(QueueTest, RefusalEndsWhenAMessageLeavesByExpiryOrSending) {
  make(R"(type { type: "qt.Command" policy { max_queue: 1 on_full: REFUSE_NEW ttl_s: 10 ack: true } })");
  auto refused = [&] { return submit_result("qt.Command", "value: 9").error == SubmitResult::Error::kQueueFull; };
  submit("qt.Command", "value: 1");
  EXPECT_TRUE(refused());
  at(11);
  manager_->expire();
  EXPECT_EQ(count(QueueEventKind::kExpired), 1);
  submit("qt.Command", "value: 2");
  EXPECT_TRUE(refused());
  ASSERT_EQ(request(one(), 1, kAnyDestination, /*ack=*/false).size(), 1u);
  EXPECT_EQ(manager_->find_queue("qt.Command")->size(), 0u);
  submit("qt.Command", "dest: 2 value: 3");
  EXPECT_TRUE(refused());
  // Sent awaiting its ack, it still holds its place; acked, it leaves.
  std::vector<Frame> frames = request(one());
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_TRUE(refused());
  manager_->on_ack(frames[0].frame_id);
  submit("qt.Command", "value: 4");
  EXPECT_TRUE(refused());
  EXPECT_EQ(manager_->stats("qt.Command").refused, 5u);
}

TEST_F(QueueTest, FirstMessageSetsTheDestinationLaterOnesMustAgreeOrBroadcast) {
  make(R"(type { type: "qt.Status" policy { value_base: 3 } }
          type { type: "qt.Command" policy { value_base: 2 } }
          type { type: "qt.Ctd" policy { value_base: 1 } })");
  submit("qt.Status", "dest: 5 value: 1");
  submit("qt.Command", "dest: 6 value: 2");  // conflicts with 5: skipped
  submit("qt.Ctd", "dest: 0 value: 3");      // broadcast: allowed
  at(10);
  auto frames = request(100);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].dest, 5);
  EXPECT_EQ(types_in(frames[0]), (std::vector<std::string>{"qt.Status", "qt.Ctd"}));
  EXPECT_EQ(manager_->find_queue("qt.Command")->size(), 1u);
  // Node 5's ack covers the whole frame, the broadcast message included.
  manager_->on_ack(frames[0].frame_id);
  EXPECT_EQ(manager_->find_queue("qt.Ctd")->size(), 0u);

  // A transmission for node 6 takes the Command.
  at(20);
  auto for_six = request(100, 1, 6);
  ASSERT_EQ(for_six.size(), 1u);
  EXPECT_EQ(types_in(for_six[0]), std::vector<std::string>{"qt.Command"});
}

TEST_F(QueueTest, StitchedFrameIsTheConcatenatedDcclEncodings) {
  make(R"(type { type: "qt.Status" policy { value_base: 3 } }
          type { type: "qt.Command" policy { value_base: 2 } }
          type { type: "qt.Ctd" policy { value_base: 1 } })");
  at(0);
  submit("qt.Status", "src: 1 dest: 2 value: 10 time: 1700000000");
  submit("qt.Command", "src: 1 dest: 2 value: 20 time: 1700000000");
  submit("qt.Ctd", "src: 1 dest: 2 value: 30 time: 1700000000");
  at(10);
  auto frames = request(64);
  ASSERT_EQ(frames.size(), 1u);
  std::string expected = codec_.encode(*message("qt.Status", "src: 1 dest: 2 value: 10 time: 1700000000")) +
                         codec_.encode(*message("qt.Command", "src: 1 dest: 2 value: 20 time: 1700000000")) +
                         codec_.encode(*message("qt.Ctd", "src: 1 dest: 2 value: 30 time: 1700000000"));
  EXPECT_EQ(dccl::to_hex(frames[0].bytes), dccl::to_hex(expected));
  EXPECT_EQ(frames[0].message_ids.size(), 3u);
}

TEST_F(QueueTest, FramesFillUntilNothingFitsAndSpanSeveralFrames) {
  make();
  for (int i = 0; i < 7; ++i) submit("qt.Status", "dest: 2 value: " + std::to_string(i));
  at(10);
  auto frames = request(2 * one() + 1, 3);  // two messages per frame, three frames
  ASSERT_EQ(frames.size(), 3u);
  for (const Frame& f : frames) EXPECT_EQ(f.message_ids.size(), 2u);
  EXPECT_EQ(manager_->find_queue("qt.Status")->in_flight(), 6u);
  EXPECT_NE(frames[0].frame_id, frames[1].frame_id);
}

TEST_F(QueueTest, AckOfAMultiMessageFrameRemovesThemAll) {
  make();
  for (int i = 0; i < 3; ++i) submit("qt.Status", "dest: 2 value: " + std::to_string(i));
  at(10);
  auto frames = request(100);
  ASSERT_EQ(frames.size(), 1u);
  ASSERT_EQ(frames[0].message_ids.size(), 3u);
  EXPECT_TRUE(frames[0].ack_requested);
  EXPECT_EQ(journal_.stored(), 3u);  // in flight: still durable
  manager_->on_ack(frames[0].frame_id);
  EXPECT_EQ(manager_->find_queue("qt.Status")->size(), 0u);
  EXPECT_EQ(manager_->stats("qt.Status").acked, 3u);
  EXPECT_EQ(journal_.stored(), 0u);
  manager_->on_ack(frames[0].frame_id);  // duplicate ack: nothing more happens
  EXPECT_EQ(manager_->stats("qt.Status").acked, 3u);
}

TEST_F(QueueTest, UnackedMessagesAreRetriedAtTheNextOpportunity) {
  make();
  int64_t id = submit("qt.Status", "dest: 2 value: 1");
  at(10);
  auto first = request(100);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_TRUE(request(100, 1, kAnyDestination).size() == 1u) << "no ack came: sent again";
  EXPECT_EQ(manager_->stats("qt.Status").retried, 1u);
  EXPECT_EQ(manager_->stats("qt.Status").sent, 2u);
  // The ack for the stale first frame no longer applies.
  manager_->on_ack(first[0].frame_id);
  EXPECT_EQ(manager_->find_queue("qt.Status")->size(), 1u);
  EXPECT_EQ(manager_->find_queue("qt.Status")->messages().front().record.id, id);
}

TEST_F(QueueTest, BroadcastOrNoAckFramesEndTheMessagesAtSending) {
  make(R"(type { type: "qt.Command" policy { ack: false } })");
  submit("qt.Status", "dest: 0 value: 1");  // broadcast cannot be acked
  at(10);
  auto broadcast = request(100);
  ASSERT_EQ(broadcast.size(), 1u);
  EXPECT_FALSE(broadcast[0].ack_requested);
  EXPECT_EQ(manager_->find_queue("qt.Status")->size(), 0u);

  submit("qt.Command", "dest: 2 value: 1");  // type does not want acks
  at(20);
  auto unacked = request(100);
  ASSERT_EQ(unacked.size(), 1u);
  EXPECT_FALSE(unacked[0].ack_requested);
  EXPECT_EQ(journal_.stored(), 0u);

  submit("qt.Status", "dest: 2 value: 1");  // the link cannot carry an ack
  at(30);
  auto no_ack_link = request(100, 1, kAnyDestination, /*ack=*/false);
  EXPECT_FALSE(no_ack_link[0].ack_requested);
  EXPECT_EQ(journal_.stored(), 0u);
}

TEST_F(QueueTest, ReceiveSplitsFramesAndKeepsWhatIsForUs) {
  make();
  std::string frame = codec_.encode(*message("qt.Status", "src: 4 dest: 1 value: 7")) +
                      codec_.encode(*message("qt.Command", "src: 4 dest: 9 value: 8")) +
                      codec_.encode(*message("qt.Ctd", "src: 4 dest: 0 value: 9"));
  auto received = manager_->receive(frame, 4);
  ASSERT_EQ(received.size(), 2u);
  EXPECT_EQ(received[0].type, "qt.Status");
  EXPECT_EQ(received[0].src, 4);
  EXPECT_EQ(received[0].dest, 1);
  EXPECT_EQ(received[1].type, "qt.Ctd");
  EXPECT_EQ(received[1].dest, 0);
  EXPECT_EQ(manager_->stats("qt.Status").received, 1u);
  EXPECT_EQ(manager_->stats("qt.Command").received, 0u);

  // Garbage after a good message: the good one is kept.
  auto partial = manager_->receive(codec_.encode(*message("qt.Status", "dest: 1 value: 1")) + "\xff\xff\x01", 4);
  EXPECT_EQ(partial.size(), 1u);
  EXPECT_EQ(manager_->malformed_frames(), 1u);
}

TEST_F(QueueTest, PromiscuousKeepsEverything) {
  make("promiscuous: true");
  std::string frame = codec_.encode(*message("qt.Command", "src: 4 dest: 9 value: 8"));
  EXPECT_EQ(manager_->receive(frame, 4).size(), 1u);
}

TEST_F(QueueTest, RolesAreFilledAtSubmit) {
  make();
  at(42);
  int64_t id = submit("qt.Status", "dest: 3 value: 1");
  ASSERT_EQ(manager_->find_queue("qt.Status")->size(), 1u);
  const QueuedMessage& queued = manager_->find_queue("qt.Status")->messages().front();
  EXPECT_EQ(queued.record.id, id);
  EXPECT_EQ(queued.record.src, kOwnId);
  EXPECT_EQ(queued.record.dest, 3);
  EXPECT_DOUBLE_EQ(queued.record.submitted_at, kStart + 42);
  auto decoded = codec_.decode(queued.encoded);
  EXPECT_EQ(decoded[0]->ShortDebugString(), "src: 1 dest: 3 value: 1 time: 1700000042");
}

TEST_F(QueueTest, RestoreBringsBackInFlightMessagesAsEligible) {
  make();
  submit("qt.Status", "dest: 2 value: 1");
  submit("qt.Status", "dest: 2 value: 2");
  at(10);
  ASSERT_EQ(request(100)[0].message_ids.size(), 2u);  // both in flight, then "crash"
  manager_.reset();
  make();
  manager_->restore();
  EXPECT_EQ(manager_->find_queue("qt.Status")->size(), 2u);
  EXPECT_EQ(manager_->find_queue("qt.Status")->in_flight(), 0u);
  at(20);
  EXPECT_EQ(request(100)[0].message_ids.size(), 2u);
}

TEST_F(QueueTest, UnknownTypesAndBadConfigAreClearErrors) {
  make();
  auto other = codec_.new_message("qt.Status");
  v1::QueueConfig bad_type;
  bad_type.add_type()->set_type("qt.Nope");
  EXPECT_THROW(QueueManager(codec_, bad_type, 1, clock_, journal_), std::invalid_argument);
  v1::QueueConfig bad_role;
  auto* entry = bad_role.add_type();
  entry->set_type("qt.Status");
  entry->mutable_roles()->set_destination_field("nope");
  try {
    QueueManager(codec_, bad_role, 1, clock_, journal_);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "queue qt.Status: destination field \"nope\" does not exist (no field \"nope\" in qt.Status)");
  }
  v1::QueueConfig bad_ttl;
  bad_ttl.mutable_defaults()->set_ttl_s(0);
  EXPECT_THROW(QueueManager(codec_, bad_ttl, 1, clock_, journal_), std::invalid_argument);
}

// The queues are lock-free because the core thread owns them: a frame built
// from a gRPC thread while the core runs would race the link. The rule is
// asserted, so such a call aborts instead of corrupting a queue.
TEST_F(QueueTest, BuildingFramesFromAnotherThreadWhileTheCoreRunsFailsItsAssertion) {
  make();
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(
      {
        core::configure_logging(v1::INFO);  // the daemon's logger: stderr
        core::EventLoop core;
        core.start();
        request(64);
      },
      "build_frames.* must run on the core thread");
}

}  // namespace
}  // namespace acomms::queue
