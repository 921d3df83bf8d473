// The queues under several links (queue/frame.h DataRequest::link and
// may_carry): a message awaiting an ACK on one link is on that link alone,
// its ACK ends it once however many links asked since, and a link is
// offered only what the node's choice of link lets it carry, judged on
// each type's priority before the request.

#include <google/protobuf/text_format.h>
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
package ql;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

class LinksInFlightTest : public testing::QueueManagerFixture {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-queue-links-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::ofstream(dir_ / "ql.proto") << kProto;
    codec_.load((dir_ / "ql.proto").string());
    v1::QueueConfig config;
    auto* entry = config.add_type();
    entry->set_type("ql.Status");
    entry->mutable_roles()->set_source_field("src");
    entry->mutable_roles()->set_destination_field("dest");
    install(std::make_unique<QueueManager>(codec_, config, testing::kOwnId, clock_, journal_));
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<Frame> request_on(int link, uint32_t frames = 1) {
    DataRequest request;
    request.link = link;
    request.max_frame_bytes = 64;
    request.max_num_frames = frames;
    return manager_->build_frames(request);
  }
};

TEST_F(LinksInFlightTest, MessageAwaitingAckOnOneLinkIsNotOfferedToAnother) {
  submit("ql.Status", "dest: 2 value: 7");
  std::vector<Frame> first = request_on(0);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_TRUE(first[0].ack_requested);
  EXPECT_TRUE(request_on(1).empty()) << "a message awaiting its ACK on link 0 went out on link 1 too";
  EXPECT_EQ(count(QueueEventKind::kRetry), 0) << "link 1's request gave up on link 0's frame";
}

TEST_F(LinksInFlightTest, LateAckOnItsLinkEndsTheMessageAfterAnotherLinkAsked) {
  submit("ql.Status", "dest: 2 value: 7");
  std::vector<Frame> first = request_on(0);
  ASSERT_EQ(first.size(), 1u);
  at(5);
  (void)request_on(1);
  manager_->on_ack(first[0].frame_id);
  EXPECT_EQ(count(QueueEventKind::kAcked), 1);
  EXPECT_EQ(manager_->find_queue("ql.Status")->size(), 0u);
  EXPECT_TRUE(request_on(0).empty());
  EXPECT_TRUE(request_on(1).empty());
}

TEST_F(LinksInFlightTest, SameLinksNextRequestRetriesIt) {
  submit("ql.Status", "dest: 2 value: 7");
  std::vector<Frame> first = request_on(0);
  ASSERT_EQ(first.size(), 1u);
  at(10);
  std::vector<Frame> again = request_on(0);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].bytes, first[0].bytes);
  EXPECT_EQ(count(QueueEventKind::kRetry), 1);
}

TEST_F(LinksInFlightTest, ReleasedLinkLetsAnotherCarryItAndItIsAckedOnce) {
  submit("ql.Status", "dest: 2 value: 7");
  std::vector<Frame> first = request_on(0);
  ASSERT_EQ(first.size(), 1u);
  manager_->release_in_flight(0);  // link 0 disabled, or its driver failed
  EXPECT_EQ(count(QueueEventKind::kRetry), 1);
  at(1);
  std::vector<Frame> other = request_on(1);
  ASSERT_EQ(other.size(), 1u) << "released, the message was not offered to link 1";
  EXPECT_EQ(other[0].bytes, first[0].bytes);
  manager_->on_ack(other[0].frame_id);
  manager_->on_ack(first[0].frame_id);  // link 0's ACK, late: nothing more
  EXPECT_EQ(count(QueueEventKind::kAcked), 1) << "acknowledged more than once";
  EXPECT_EQ(manager_->find_queue("ql.Status")->size(), 0u);
}

TEST_F(LinksInFlightTest, MayCarryKeepsMessagesOffALinkAndSeesThePriorityBeforeTheRequest) {
  submit("ql.Status", "dest: 2 value: 1");
  submit("ql.Status", "dest: 2 value: 2");
  at(900);  // P = 1 * 900 / 1800
  std::vector<std::pair<int32_t, double>> asked;
  DataRequest refused;
  refused.link = 1;
  refused.max_frame_bytes = 64;
  refused.may_carry = [&](const std::string& type, int32_t dest, double priority) {
    EXPECT_EQ(type, "ql.Status");
    asked.emplace_back(dest, priority);
    return false;
  };
  EXPECT_TRUE(manager_->build_frames(refused).empty());
  ASSERT_FALSE(asked.empty());
  EXPECT_EQ(asked[0].first, 2);
  EXPECT_NEAR(asked[0].second, 0.5, 1e-9);

  asked.clear();
  DataRequest allowed = refused;
  allowed.may_carry = [&](const std::string&, int32_t dest, double priority) {
    asked.emplace_back(dest, priority);
    return priority > 0.4;
  };
  std::vector<Frame> frames = manager_->build_frames(allowed);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].message_ids.size(), 2u) << "the second message was judged on P after the first won";
  ASSERT_EQ(asked.size(), 2u);
  EXPECT_NEAR(asked[1].second, 0.5, 1e-9);
}

}  // namespace
}  // namespace acomms::queue
