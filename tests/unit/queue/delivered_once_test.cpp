// "A message is delivered at most once, for as long as its sender may
// resend it" (queue_manager.h), on the simulated clock: each type's
// duplicate window is at least its ttl, a message stamped longer ago than
// the window (plus the clock skew allowed) is refused as stale, a Submit
// ttl_s past the window is refused, and a sender whose ACKs are lost for
// longer than the old 300 s window still has each message delivered once.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include "queue_manager_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;

// Order is stamped (a timestamp role); Note is not.
constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package qo;
message Order {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
  optional double time = 4 [(dccl.field) = { min: 0 max: 2000000000 precision: 0 }];
}
message Note {
  option (dccl.msg) = { codec_version: 4 id: 3 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

using testing::kOwnId;
using testing::kStart;

constexpr int32_t kPeer = 4;

class DeliveredOnceTest : public testing::QueueManagerFixture {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("acomms-queue-once-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::ofstream(dir_ / "qo.proto") << kProto;
    codec_.load((dir_ / "qo.proto").string());
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Order gets src/dest/time roles, Note src/dest; `text` is more QueueConfig.
  static v1::QueueConfig config(const std::string& text) {
    v1::QueueConfig config;
    EXPECT_TRUE(pb::TextFormat::ParseFromString(text, &config)) << text;
    for (const char* type : {"qo.Order", "qo.Note"}) {
      v1::QueueTypeConfig* entry = nullptr;
      for (auto& listed : *config.mutable_type()) {
        if (listed.type() == type) entry = &listed;
      }
      if (entry == nullptr) entry = config.add_type();
      entry->set_type(type);
      entry->mutable_roles()->set_source_field("src");
      entry->mutable_roles()->set_destination_field("dest");
      if (entry->type() == "qo.Order") entry->mutable_roles()->set_timestamp_field("time");
    }
    return config;
  }
  QueueManager& make(const std::string& text = "") {
    return install(std::make_unique<QueueManager>(codec_, config(text), kOwnId, clock_, journal_));
  }

  // An Order from the peer to us, stamped `stamped_after_start`.
  std::string order(int value, double stamped_after_start) {
    return encode("qo.Order", "src: 4 dest: 1 value: " + std::to_string(value) +
                                  " time: " + std::to_string(kStart + stamped_after_start));
  }
};

// ------------------------------------------------------------ the window

TEST_F(DeliveredOnceTest, WindowIsTheLongerOfTheConfiguredWindowAndTheTypesTtl) {
  make("duplicate_window_s: 300 defaults { ttl_s: 100 } type { type: \"qo.Note\" policy { ttl_s: 900 } }");
  EXPECT_EQ(manager_->duplicate_window("qo.Order"), 300);
  EXPECT_EQ(manager_->duplicate_window("qo.Note"), 900);
  EXPECT_THROW(manager_->duplicate_window("qo.Nothing"), UnknownTypeError);
}

// A type without a timestamp role can only go by the window: a copy arriving
// within the ttl is a resend, one after it is taken as new (the documented
// limit: the sender no longer resends by then).
TEST_F(DeliveredOnceTest, UnstampedResendWithinTheTypesTtlIsADuplicateEvenPastTheConfiguredWindow) {
  make("duplicate_window_s: 300 type { type: \"qo.Note\" policy { ttl_s: 900 } }");
  std::string note = encode("qo.Note", "src: 4 dest: 1 value: 5");
  ASSERT_EQ(manager_->receive(note, kPeer).size(), 1u);
  at(305);
  EXPECT_TRUE(manager_->receive(note, kPeer).empty()) << "resent after 300 s: delivered twice";
  at(899);
  EXPECT_TRUE(manager_->receive(note, kPeer).empty()) << "resent within the ttl: delivered twice";
  EXPECT_EQ(manager_->duplicates(), 2u);
  at(901);
  EXPECT_EQ(manager_->receive(note, kPeer).size(), 1u) << "past the window a Note is taken as new";
  EXPECT_EQ(manager_->stale_refused(), 0u);
}

// A type that drops repeats by a sequence number of its own (the telemetry
// types: identical deltas are normal on a straight leg) is kept out of the
// filter: every copy is passed on, and its ttl is not bounded by a window.
TEST_F(DeliveredOnceTest, TypeWithTheDuplicateFilterOffPassesEveryCopyOn) {
  make("duplicate_window_s: 300 type { type: \"qo.Note\" duplicate_filter: false policy { ttl_s: 900 } }");
  std::string note = encode("qo.Note", "src: 4 dest: 1 value: 5");
  EXPECT_EQ(manager_->receive(note, kPeer).size(), 1u);
  at(10);
  EXPECT_EQ(manager_->receive(note, kPeer).size(), 1u) << "an identical Note was taken as a resend";
  EXPECT_EQ(manager_->duplicates(), 0u);
  EXPECT_EQ(manager_->duplicate_window("qo.Note"), 0);
  // Other types keep their filter.
  std::string first = order(1, 10);
  EXPECT_EQ(manager_->receive(first, kPeer).size(), 1u);
  EXPECT_TRUE(manager_->receive(first, kPeer).empty());
}

TEST_F(DeliveredOnceTest, WindowOfATtlLongerTypeHoldsAcrossARestart) {
  const std::string text = "duplicate_window_s: 60 type { type: \"qo.Note\" policy { ttl_s: 600 } }";
  make(text);
  std::string note = encode("qo.Note", "src: 4 dest: 1 value: 8");
  ASSERT_EQ(manager_->receive(note, kPeer).size(), 1u);
  at(500);
  make(text);  // the restarted process: same journal, empty memory
  manager_->restore();
  at(590);
  EXPECT_TRUE(manager_->receive(note, kPeer).empty()) << "the resend after the restart was passed on twice";
  EXPECT_EQ(manager_->duplicates(), 1u);
}

// ------------------------------------------------------------ stale

TEST_F(DeliveredOnceTest, StampedLongerAgoThanWindowPlusSkewIsRefusedAsStale) {
  make("duplicate_window_s: 300 clock_skew_s: 60 defaults { ttl_s: 600 }");
  at(2000);
  // Window 600 s, plus 60 s skew: the bound is 660 s.
  EXPECT_EQ(manager_->receive(order(1, 2000 - 659), kPeer).size(), 1u);
  EXPECT_TRUE(manager_->receive(order(2, 2000 - 661), kPeer).empty());
  EXPECT_EQ(manager_->stale_refused(), 1u);
  EXPECT_EQ(manager_->duplicates(), 0u);
  EXPECT_EQ(manager_->stats("qo.Order").received, 1u) << "a stale message counted as received";
  EXPECT_EQ(count(QueueEventKind::kReceived), 1);
  // A message stamped ahead of our clock (the sender's runs fast) is fresh.
  EXPECT_EQ(manager_->receive(order(3, 2100), kPeer).size(), 1u);
  // Types without a timestamp role are never stale.
  EXPECT_EQ(manager_->receive(encode("qo.Note", "src: 4 dest: 1 value: 1"), kPeer).size(), 1u);
  EXPECT_EQ(manager_->stale_refused(), 1u);
}

// Logs go to a string while it lives, then back to the previous logger.
class CapturedLog {
 public:
  CapturedLog() : previous_(spdlog::default_logger()) {
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(text_);
    sink->set_pattern("%l %v");
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("captured", sink));
  }
  ~CapturedLog() { spdlog::set_default_logger(previous_); }
  // Lines containing `part`.
  int lines_with(const std::string& part) const {
    std::istringstream lines(text_.str());
    int n = 0;
    for (std::string line; std::getline(lines, line);) n += line.find(part) != std::string::npos;
    return n;
  }
  std::string text() const { return text_.str(); }

 private:
  std::ostringstream text_;
  std::shared_ptr<spdlog::logger> previous_;
};

TEST_F(DeliveredOnceTest, AStaleBurstIsLoggedOnceAndItsCountWhenAFreshMessageEndsIt) {
  make("duplicate_window_s: 300 clock_skew_s: 0 defaults { ttl_s: 300 }");
  at(5000);
  CapturedLog log;
  for (int i = 0; i < 50; ++i) EXPECT_TRUE(manager_->receive(order(i, 1000), kPeer).empty());
  EXPECT_EQ(log.lines_with("refused as stale"), 1) << log.text();
  EXPECT_EQ(manager_->stale_refused(), 50u);
  ASSERT_EQ(manager_->receive(order(60, 4990), kPeer).size(), 1u);
  EXPECT_EQ(log.lines_with("50 stale messages refused"), 1) << log.text();
  // The next burst is logged again.
  EXPECT_TRUE(manager_->receive(order(61, 1000), kPeer).empty());
  EXPECT_EQ(log.lines_with("refused as stale"), 2) << log.text();
}

// However the clocks differ (within the skew allowed) and whenever the
// resend comes, a stamped message is delivered once: while the filter holds
// it, as a duplicate; after that, it is stale.
TEST_F(DeliveredOnceTest, StampedResendIsNeverDeliveredTwiceWhateverItsDelay) {
  make("duplicate_window_s: 300 clock_skew_s: 60 defaults { ttl_s: 600 }");
  int value = 0;
  for (double skew : {-60.0, 0.0, 60.0}) {   // our clock minus the sender's
    for (double delay = 0; delay <= 3000; delay += 15) {
      double stamped = 10000.0 * (value + 1);  // sender's clock, in the past
      at(stamped + skew);                      // first copy arrives at once
      std::string copy = order(value++ % 1000, stamped);
      ASSERT_EQ(manager_->receive(copy, kPeer).size(), 1u) << "first copy, skew " << skew;
      at(stamped + skew + delay);
      EXPECT_TRUE(manager_->receive(copy, kPeer).empty()) << "skew " << skew << ", resent after " << delay << " s";
    }
  }
  EXPECT_GT(manager_->stale_refused(), 0u);
  EXPECT_GT(manager_->duplicates(), 0u);
}

// ------------------------------------------------------------ Submit ttl

TEST_F(DeliveredOnceTest, SubmitTtlLongerThanTheWindowIsRefusedNamingTheBound) {
  make("duplicate_window_s: 300 defaults { ttl_s: 600 }");
  SubmitResult refused = submit_result("qo.Order", "dest: 4 value: 1", 601);
  EXPECT_EQ(refused.error, SubmitResult::Error::kInvalidMessage);
  EXPECT_NE(refused.text.find("ttl_s 601"), std::string::npos) << refused.text;
  EXPECT_NE(refused.text.find("window of 600 s"), std::string::npos) << refused.text;
  EXPECT_EQ(manager_->find_queue("qo.Order")->size(), 0u);
  EXPECT_EQ(count(QueueEventKind::kQueued), 0) << "a refused Submit left a trace in the store";
  submit("qo.Order", "dest: 4 value: 2", 600);
  submit("qo.Order", "dest: 4 value: 3", 0);  // the queue's ttl
}

TEST_F(DeliveredOnceTest, WithTheFilterOffAnyTtlIsAccepted) {
  make("duplicate_window_s: 0 defaults { ttl_s: 600 }");
  submit("qo.Order", "dest: 4 value: 1", 1e6);
  EXPECT_EQ(manager_->duplicate_window("qo.Order"), 0);
  at(5000);
  EXPECT_EQ(manager_->receive(order(1, 0), kPeer).size(), 1u) << "stale check on with the filter off";
}

// ------------------------------------------------------------ lost ACKs

// The issue's failure: the sender kept resending (its ACKs were lost) past
// the old 300 s window, and the resend was delivered again. Here both ends
// are real QueueManagers on one simulated clock; every ACK is lost for the
// first 900 s, the sender offers a frame every 10 s, and each message must
// reach the receiver exactly once.
TEST_F(DeliveredOnceTest, AcksLostForLongerThanTheOldWindowDeliverEachMessageOnce) {
  make("defaults { ttl_s: 1800 }");  // the sender, node 1; duplicate_window_s the default 300
  MemoryJournal receiver_journal;
  QueueManager receiver(codec_, config("defaults { ttl_s: 1800 }"), kPeer, clock_, receiver_journal);
  receiver.restore();

  constexpr int kMessages = 12;
  for (int i = 0; i < kMessages; ++i) submit("qo.Order", "dest: 4 value: " + std::to_string(i));
  for (int i = 0; i < kMessages; ++i) submit("qo.Note", "dest: 4 value: " + std::to_string(i));
  const uint32_t room = static_cast<uint32_t>(2 * order(0, 0).size());

  std::map<std::string, int> delivered;  // "type value" -> copies
  int frames_sent = 0;
  for (double t = 10; t <= 1300; t += 10) {
    at(t);
    for (const Frame& frame : manager_->build_frames(DataRequest{kPeer, room, 1, true})) {
      ++frames_sent;
      for (const ReceivedMessage& m : receiver.receive(frame.bytes, kOwnId)) {
        const auto* value = m.message->GetDescriptor()->FindFieldByName("value");
        ++delivered[m.type + " " + std::to_string(m.message->GetReflection()->GetInt32(*m.message, value))];
      }
      if (t > 900) manager_->on_ack(frame.frame_id);  // the ACKs get through at last
    }
  }
  EXPECT_EQ(delivered.size(), 2u * kMessages) << "not every message was delivered";
  for (const auto& [message, copies] : delivered) EXPECT_EQ(copies, 1) << message << " delivered " << copies << " times";
  EXPECT_GT(frames_sent, 90) << "the sender did not keep resending";
  EXPECT_GT(receiver.duplicates(), 0u);
  EXPECT_EQ(receiver.stale_refused(), 0u);
  EXPECT_EQ(manager_->find_queue("qo.Order")->size(), 0u) << "the late ACKs did not clear the sender";
  EXPECT_EQ(manager_->find_queue("qo.Note")->size(), 0u);
}

}  // namespace
}  // namespace acomms::queue
