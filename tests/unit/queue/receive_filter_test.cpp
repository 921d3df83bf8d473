// The ReceiveFilter on its own (receive_filter.h): a retransmission is
// passed on once, a message stamped longer ago than its type's window plus
// the clock skew is refused as stale, the window is never shorter than the
// type's ttl, a window of 0 turns the filter off, and what the event log
// says was received before a restart still counts as seen. The same rules
// through QueueManager::receive: delivered_once_test.cpp.

#include "queue/receive_filter.h"

#include <google/protobuf/descriptor.pb.h>
#include <google/protobuf/dynamic_message.h>
#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "queue/memory_journal.h"

namespace acomms::queue {
namespace {

namespace pb = google::protobuf;

constexpr double kNow = 1'700'000'000;
constexpr int32_t kPeer = 4;

// rf.Stamped {src, time, value}: a type with source and timestamp roles,
// built in memory so the filter is tested without DCCL.
class ReceiveFilterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    pb::FileDescriptorProto file;
    file.set_name("rf.proto");
    file.set_package("rf");
    file.set_syntax("proto2");
    pb::DescriptorProto* type = file.add_message_type();
    type->set_name("Stamped");
    add_field(type, "src", 1, pb::FieldDescriptorProto::TYPE_INT32);
    add_field(type, "time", 2, pb::FieldDescriptorProto::TYPE_DOUBLE);
    add_field(type, "value", 3, pb::FieldDescriptorProto::TYPE_INT32);
    ASSERT_NE(pool_.BuildFile(file), nullptr);
    descriptor_ = pool_.FindMessageTypeByName("rf.Stamped");
    v1::QueueRoles stamped;
    stamped.set_source_field("src");
    stamped.set_timestamp_field("time");
    stamped_roles_ = MessageRoles(descriptor_, stamped);
    v1::QueueRoles unstamped;
    unstamped.set_source_field("src");
    unstamped_roles_ = MessageRoles(descriptor_, unstamped);
  }

  static void add_field(pb::DescriptorProto* type, const char* name, int number, pb::FieldDescriptorProto::Type kind) {
    pb::FieldDescriptorProto* field = type->add_field();
    field->set_name(name);
    field->set_number(number);
    field->set_type(kind);
    field->set_label(pb::FieldDescriptorProto::LABEL_OPTIONAL);
  }

  // A received rf.Stamped from kPeer; `encoded` stands for its DCCL bytes.
  ReceivedMessage received(const std::string& encoded, std::optional<double> stamped) {
    ReceivedMessage out;
    out.type = "rf.Stamped";
    out.message.reset(factory_.GetPrototype(descriptor_)->New());
    const pb::Reflection* reflection = out.message->GetReflection();
    reflection->SetInt32(out.message.get(), descriptor_->FindFieldByName("src"), kPeer);
    if (stamped) reflection->SetDouble(out.message.get(), descriptor_->FindFieldByName("time"), *stamped);
    out.encoded = encoded;
    out.src = kPeer;
    out.time = kNow;
    return out;
  }

  static v1::QueueConfig config(std::optional<double> window_s, std::optional<double> skew_s) {
    v1::QueueConfig config;
    if (window_s) config.set_duplicate_window_s(*window_s);
    if (skew_s) config.set_clock_skew_s(*skew_s);
    return config;
  }

  pb::DescriptorPool pool_;
  pb::DynamicMessageFactory factory_{&pool_};
  const pb::Descriptor* descriptor_ = nullptr;
  MessageRoles stamped_roles_;
  MessageRoles unstamped_roles_;
};

TEST_F(ReceiveFilterTest, PassesTheFirstCopyAndRefusesItsRetransmission) {
  ReceiveFilter filter(config(300, 60));
  EXPECT_EQ(filter.add_type("rf.Stamped", 100, unstamped_roles_), 300);
  EXPECT_TRUE(filter.admit(received("abc", std::nullopt), unstamped_roles_, kNow));
  EXPECT_FALSE(filter.admit(received("abc", std::nullopt), unstamped_roles_, kNow + 10));
  EXPECT_TRUE(filter.admit(received("abd", std::nullopt), unstamped_roles_, kNow + 10));
  EXPECT_EQ(filter.duplicates(), 1u);
  EXPECT_EQ(filter.stale_refused(), 0u);
}

TEST_F(ReceiveFilterTest, ARetransmissionAfterTheWindowIsPassedOnAgain) {
  ReceiveFilter filter(config(300, 60));
  filter.add_type("rf.Stamped", 100, unstamped_roles_);
  EXPECT_TRUE(filter.admit(received("abc", std::nullopt), unstamped_roles_, kNow));
  EXPECT_TRUE(filter.admit(received("abc", std::nullopt), unstamped_roles_, kNow + 301));
  EXPECT_EQ(filter.duplicates(), 0u);
}

TEST_F(ReceiveFilterTest, WindowIsNeverShorterThanTheTtl) {
  ReceiveFilter filter(config(300, 60));
  EXPECT_EQ(filter.add_type("rf.Stamped", 900, unstamped_roles_), 900);
  EXPECT_EQ(filter.longest_window_s(), 900);
  EXPECT_TRUE(filter.admit(received("abc", std::nullopt), unstamped_roles_, kNow));
  EXPECT_FALSE(filter.admit(received("abc", std::nullopt), unstamped_roles_, kNow + 899));
}

TEST_F(ReceiveFilterTest, AStampedTypeRemembersForTheWindowPlusTwiceTheSkew) {
  ReceiveFilter filter(config(300, 60));
  EXPECT_EQ(filter.add_type("rf.Stamped", 100, stamped_roles_), 300);
  EXPECT_EQ(filter.longest_window_s(), 420);
}

TEST_F(ReceiveFilterTest, StampedLongerAgoThanWindowPlusSkewIsRefusedAsStale) {
  ReceiveFilter filter(config(300, 60));
  filter.add_type("rf.Stamped", 100, stamped_roles_);
  EXPECT_FALSE(filter.admit(received("old", kNow - 361), stamped_roles_, kNow));
  EXPECT_EQ(filter.stale_refused(), 1u);
  EXPECT_TRUE(filter.admit(received("new", kNow - 359), stamped_roles_, kNow));
  // Unstamped, the same type cannot be judged stale.
  EXPECT_TRUE(filter.admit(received("none", std::nullopt), stamped_roles_, kNow));
  EXPECT_EQ(filter.stale_refused(), 1u);
  EXPECT_EQ(filter.duplicates(), 0u);
}

TEST_F(ReceiveFilterTest, AZeroWindowTurnsTheFilterOff) {
  ReceiveFilter filter(config(0, 60));
  EXPECT_EQ(filter.add_type("rf.Stamped", 100, stamped_roles_), 0);
  EXPECT_EQ(filter.longest_window_s(), 0);
  EXPECT_TRUE(filter.admit(received("abc", kNow - 10'000), stamped_roles_, kNow));
  EXPECT_TRUE(filter.admit(received("abc", kNow - 10'000), stamped_roles_, kNow));
  EXPECT_EQ(filter.duplicates(), 0u);
  EXPECT_EQ(filter.stale_refused(), 0u);
}

TEST_F(ReceiveFilterTest, UnsetWindowIsThreeHundredSeconds) {
  ReceiveFilter filter(config(std::nullopt, std::nullopt));
  EXPECT_EQ(filter.add_type("rf.Stamped", 100, unstamped_roles_), 300);
}

TEST_F(ReceiveFilterTest, ATypeNeverAddedIsAlwaysPassedOn) {
  ReceiveFilter filter(config(300, 60));
  EXPECT_TRUE(filter.admit(received("abc", kNow - 10'000), stamped_roles_, kNow));
  EXPECT_TRUE(filter.admit(received("abc", kNow - 10'000), stamped_roles_, kNow));
}

TEST_F(ReceiveFilterTest, RefillRemembersWhatWasReceivedWithinTheWindow) {
  MemoryJournal journal;
  auto received_event = [&](const std::string& encoded, double time) {
    QueueEvent event;
    event.kind = QueueEventKind::kReceived;
    event.type = "rf.Stamped";
    event.src = kPeer;
    event.encoded = encoded;
    event.time = time;
    journal.record(event);
  };
  received_event("forgotten", kNow - 301);
  received_event("recent", kNow - 299);
  ReceiveFilter filter(config(300, 60));
  filter.add_type("rf.Stamped", 100, unstamped_roles_);
  filter.refill(journal, kNow);
  EXPECT_FALSE(filter.admit(received("recent", std::nullopt), unstamped_roles_, kNow));
  EXPECT_TRUE(filter.admit(received("forgotten", std::nullopt), unstamped_roles_, kNow));
  EXPECT_EQ(filter.duplicates(), 1u);
}

TEST_F(ReceiveFilterTest, NegativeOrNonFiniteSettingsAreRefusedNamingTheField) {
  try {
    ReceiveFilter filter(config(-1, std::nullopt));
    FAIL() << "a negative window was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("queue.duplicate_window_s"), std::string::npos) << e.what();
  }
  try {
    ReceiveFilter filter(config(std::nullopt, std::numeric_limits<double>::infinity()));
    FAIL() << "an infinite clock skew was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("queue.clock_skew_s"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace acomms::queue
