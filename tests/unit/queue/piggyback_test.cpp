// The piggyback seam (queue/piggyback.h): a node's own few bytes go only in
// frame space no queued message could use, last in their frame, and on the
// receive side they are handed over wherever they sit in a frame, without
// losing the messages before them.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "queue_manager_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package pg;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

constexpr uint32_t kId = 300;  // header ((300 << 1) | 1) LE: 0x59 0x02

// Four bytes: the id header and two of its own, sent whenever there is room.
class FakePiggyback final : public Piggyback {
 public:
  uint32_t dccl_id() const override { return kId; }
  std::string take(int link, size_t room, double) override {
    rooms.push_back(room);
    if (room < 4) return {};
    links.push_back(link);
    return std::string("\x59\x02pb", 4);
  }
  size_t on_received(std::string_view rest, int32_t src, int, double) override {
    if (rest.size() < 4) return 0;
    heard.emplace_back(rest.substr(0, 4));
    sources.push_back(src);
    return 4;
  }
  std::vector<size_t> rooms;
  std::vector<int> links;
  std::vector<std::string> heard;
  std::vector<int32_t> sources;
};

class PiggybackTest : public testing::QueueManagerFixture {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-queue-piggyback-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::ofstream(dir_ / "pg.proto") << kProto;
    codec_.load((dir_ / "pg.proto").string());
    v1::QueueConfig config;
    auto* entry = config.add_type();
    entry->set_type("pg.Status");
    entry->mutable_roles()->set_source_field("src");
    entry->mutable_roles()->set_destination_field("dest");
    install(std::make_unique<QueueManager>(codec_, config, testing::kOwnId, clock_, journal_));
    manager_->set_piggyback(&piggyback_);
    message_bytes_ = encode("pg.Status", "src: 1 dest: 2 value: 7").size();
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<Frame> request(uint32_t frame_bytes, uint32_t frames = 1, int link = 0, bool in_slot = true) {
    DataRequest r;
    r.link = link;
    r.in_slot = in_slot;
    r.max_frame_bytes = frame_bytes;
    r.max_num_frames = frames;
    r.ack_requested = false;
    return manager_->build_frames(r);
  }

  FakePiggyback piggyback_;
  size_t message_bytes_ = 0;
};

TEST_F(PiggybackTest, GoesLastInWhatTheMessagesLeftOfTheFrame) {
  submit("pg.Status", "src: 1 dest: 2 value: 7");
  submit("pg.Status", "src: 1 dest: 2 value: 8");
  std::vector<Frame> frames = request(static_cast<uint32_t>(2 * message_bytes_ + 4));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].message_ids.size(), 2u);  // both messages went
  EXPECT_EQ(frames[0].bytes.size(), 2 * message_bytes_ + 4);
  EXPECT_EQ(frames[0].bytes.substr(2 * message_bytes_), std::string("\x59\x02pb", 4));
}

TEST_F(PiggybackTest, NeverTakesAPlaceAMessageCouldUse) {
  submit("pg.Status", "src: 1 dest: 2 value: 7");
  submit("pg.Status", "src: 1 dest: 2 value: 8");
  // Room for both messages and 3 bytes: the messages go, the piggyback does
  // not (it is asked only about the 3 bytes left).
  std::vector<Frame> frames = request(static_cast<uint32_t>(2 * message_bytes_ + 3));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].message_ids.size(), 2u);
  EXPECT_EQ(frames[0].bytes.size(), 2 * message_bytes_);
  ASSERT_EQ(piggyback_.rooms.size(), 1u);
  EXPECT_EQ(piggyback_.rooms[0], 3u);
}

TEST_F(PiggybackTest, TakesAFrameOfItsOwnWhenNoMessageWantedOne) {
  submit("pg.Status", "src: 1 dest: 2 value: 7");
  std::vector<Frame> frames = request(static_cast<uint32_t>(message_bytes_), 2, 1);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].message_ids.size(), 1u);
  EXPECT_EQ(frames[1].message_ids.size(), 0u);
  EXPECT_EQ(frames[1].bytes, std::string("\x59\x02pb", 4));
  EXPECT_EQ(piggyback_.links, std::vector<int>{1});
  // Nothing queued at all: a broadcast frame of its own.
  frames = request(32);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].dest, kBroadcast);
  EXPECT_EQ(frames[0].bytes, std::string("\x59\x02pb", 4));
}

// A satellite session is held only for what the queues give: the
// piggyback rides with queued messages there, never alone.
TEST_F(PiggybackTest, NeverMakesASlotlessLinkTransmit) {
  EXPECT_TRUE(request(32, 1, 0, false).empty());
  EXPECT_TRUE(piggyback_.links.empty());
  submit("pg.Status", "src: 1 dest: 2 value: 7");
  std::vector<Frame> frames = request(32, 1, 0, false);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].bytes.substr(message_bytes_), std::string("\x59\x02pb", 4));
}

TEST_F(PiggybackTest, AFullTransmissionCarriesNone) {
  submit("pg.Status", "src: 1 dest: 2 value: 7");
  std::vector<Frame> frames = request(static_cast<uint32_t>(message_bytes_), 1);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].bytes.size(), message_bytes_);
  EXPECT_TRUE(piggyback_.links.empty());
}

TEST_F(PiggybackTest, IsHandedOverOnReceiveAfterTheMessagesBeforeIt) {
  const std::string frame = encode("pg.Status", "src: 2 dest: 1 value: 7") + std::string("\x59\x02pb", 4);
  std::vector<ReceivedMessage> received = manager_->receive(frame, 2);
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(received[0].type, "pg.Status");
  ASSERT_EQ(piggyback_.heard.size(), 1u);
  EXPECT_EQ(piggyback_.sources, std::vector<int32_t>{2});
  EXPECT_EQ(manager_->malformed_frames(), 0u);
}

TEST_F(PiggybackTest, AMalformedOneEndsTheFrameLikeUndecodableBytes) {
  const std::string frame = encode("pg.Status", "src: 2 dest: 1 value: 7") + std::string("\x59\x02", 2);
  std::vector<ReceivedMessage> received = manager_->receive(frame, 2);
  EXPECT_EQ(received.size(), 1u);  // what came before is kept
  EXPECT_TRUE(piggyback_.heard.empty());
  EXPECT_EQ(manager_->malformed_frames(), 1u);
}

// A node without one (an older acommsd, consistency disabled in a future
// way): the piggyback is an unknown id at the end of the frame, and the
// messages before it are still delivered.
TEST_F(PiggybackTest, AReceiverWithoutItLosesNothingBeforeIt) {
  manager_->set_piggyback(nullptr);
  const std::string frame = encode("pg.Status", "src: 2 dest: 1 value: 7") + std::string("\x59\x02pb", 4);
  std::vector<ReceivedMessage> received = manager_->receive(frame, 2);
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(received[0].type, "pg.Status");
}

}  // namespace
}  // namespace acomms::queue
