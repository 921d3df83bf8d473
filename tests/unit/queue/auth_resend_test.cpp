// A Command whose first copy arrived but whose ack was lost, and whose
// sender then died (SIGKILL) and came back, is delivered once: the sender's
// queue keeps the seal in its SQLite store (migrations/0012_queued_sealed.sql)
// and resends the very bytes it sent before, which the receiver refuses as a
// copy of one it accepted (counted as replayed, never delivered again). The
// receiver's link acknowledges the frame all the same (software acks are per
// frame, whatever the queue made of its messages: link/driver_sequence.h),
// and that ack ends the message at the sender.
//
// Also here, on the same two queues: a sealed message counts its trailer in
// the frame it goes in (a frame never exceeds the link's max_frame_bytes),
// the same bytes from two senders are two messages (auth_guard.h), and a
// recorded Command replayed minutes later, also after the receiver's
// restart over its store, is refused.
// Simulated clock throughout; the sender's store is real.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/clock.h"
#include "dccl/codec.h"
#include "dccl/message_auth.h"
#include "queue/auth_guard.h"
#include "queue/memory_journal.h"
#include "queue/queue_manager.h"
#include "queue/submitter.h"
#include "store/migration.h"
#include "store/sqlite.h"
#include "store_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;

constexpr double kStart = 1'700'000'000;
constexpr int32_t kVehicle = 1;  // the receiver
constexpr int32_t kTopside = 2;  // the sender
constexpr double kWindow = 600;

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package qr;
message Command {
  option (dccl.msg) = { codec_version: 4 id: 5 max_bytes: 32 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

dccl::Keyring fleet_ring() {
  dccl::Keyring ring;
  ring.keys[1].key = std::string(16, 'f');
  ring.sign_id = 1;
  return ring;
}

v1::QueueConfig queue_config() {
  v1::QueueConfig config;
  EXPECT_TRUE(pb::TextFormat::ParseFromString(
      "type { type: \"qr.Command\" policy { ttl_s: 300 } roles { source_field: \"src\" destination_field: \"dest\" } }",
      &config));
  return config;
}

class AuthResendTest : public acomms::testing::StoreFixture {
 protected:
  void SetUp() override {
    std::ofstream(dir_.path() / "qr.proto") << kProto;
    for (dccl::Codec* codec : {&topside_codec_, &vehicle_codec_}) {
      codec->load((dir_.path() / "qr.proto").string());
      codec->set_clock([this] { return clock_.now_seconds(); });
    }
    topside_codec_.set_authentication(std::make_shared<dccl::MessageAuthenticator>(64, fleet_ring(), kTopside),
                                      {"qr.Command"});
    vehicle_codec_.set_authentication(std::make_shared<dccl::MessageAuthenticator>(64, fleet_ring(), kVehicle),
                                      {"qr.Command"});
    vehicle_ = std::make_unique<QueueManager>(vehicle_codec_, queue_config(), kVehicle, clock_, vehicle_journal_);
    vehicle_->authenticate("qr.Command", kWindow);
    vehicle_->restore();
    start_topside();
  }
  void TearDown() override {
    stop_topside();
    StoreFixture::TearDown();
  }

  // The topside's acommsd over its store in the test's directory.
  void start_topside() {
    open_store(dir_.path() / "topside");
    topside_ = std::make_unique<QueueManager>(topside_codec_, queue_config(), kTopside, clock_, *journal_);
    topside_->authenticate("qr.Command", kWindow);
    topside_->restore();
    submitter_ = std::make_unique<Submitter>(*topside_, [this](std::function<void()> work) {
      held_.push_back(std::move(work));
    });
  }
  // SIGKILL: nothing more happens in the process; what the store committed
  // stays (a Submit is answered only once its message is committed).
  // (The writer finishes what was posted first: the fixture closes the
  // journal before the writer that would still run its work.)
  void stop_topside() {
    if (journal_) journal_->flush();
    submitter_.reset();
    topside_.reset();
    close_store();
  }

  void submit(int value) {
    auto m = topside_codec_.new_message("qr.Command");
    ASSERT_TRUE(pb::TextFormat::ParseFromString("dest: 1 value: " + std::to_string(value), m.get()));
    bool ok = false;
    submitter_->submit(*m, 0, [&ok](SubmitResult r) { ok = r.ok(); });
    journal_->flush();  // the commit, on the writer's thread
    for (auto& work : held_) work();  // then the core's part, here
    held_.clear();
    ASSERT_TRUE(ok);
  }

  // The topside's next transmission to the vehicle, one frame of `room` bytes.
  std::vector<Frame> transmit(uint32_t room = 32) {
    DataRequest request;
    request.dest = kVehicle;
    request.max_frame_bytes = room;
    request.ack_requested = true;
    return topside_->build_frames(request);
  }

  void at(double seconds_after_start) {
    clock_.set(core::Clock::time_point(std::chrono::duration_cast<core::Clock::time_point::duration>(
        std::chrono::duration<double>(kStart + seconds_after_start))));
  }

  core::SimulatedClock clock_{core::Clock::time_point(std::chrono::seconds(static_cast<int64_t>(kStart)))};
  dccl::Codec topside_codec_;
  dccl::Codec vehicle_codec_;
  MemoryJournal vehicle_journal_;
  std::unique_ptr<QueueManager> vehicle_;
  std::unique_ptr<QueueManager> topside_;
  std::unique_ptr<Submitter> submitter_;
  std::vector<std::function<void()>> held_;
};

TEST_F(AuthResendTest, ResendAfterTheSendersRestartIsByteIdenticalAcknowledgedAndNotDeliveredAgain) {
  submit(7);
  std::vector<Frame> first = transmit();
  ASSERT_EQ(first.size(), 1u);
  ASSERT_EQ(vehicle_->receive(first[0].bytes, kTopside).size(), 1u) << "the first copy arrives";
  // The ack is lost; the topside is killed and restarted a minute later.
  at(60);
  stop_topside();
  start_topside();
  EXPECT_EQ(topside_->find_queue("qr.Command")->size(), 1u) << "still owed to the vehicle";
  std::vector<Frame> resent = transmit();
  ASSERT_EQ(resent.size(), 1u);
  EXPECT_EQ(resent[0].bytes, first[0].bytes) << "the resend is the message as first sealed";
  EXPECT_TRUE(vehicle_->receive(resent[0].bytes, kTopside).empty()) << "not delivered twice";
  EXPECT_EQ(vehicle_->auth_refusals().replayed, 1u);
  // The vehicle's link acknowledges the frame (per frame, whatever its
  // messages were): that ends the message at the topside.
  topside_->on_ack(resent[0].frame_id);
  EXPECT_EQ(topside_->find_queue("qr.Command")->size(), 0u);
  EXPECT_EQ(journal_->load().size(), 0u) << "gone from the store too";
  int received = 0;
  for (const QueueEvent& e : vehicle_journal_.events()) received += e.kind == QueueEventKind::kReceived;
  EXPECT_EQ(received, 1);
}

TEST_F(AuthResendTest, AStoredSealUnderARetiredKeyIsSealedAgainAtRestart) {
  submit(8);
  std::vector<Frame> first = transmit();
  ASSERT_EQ(first.size(), 1u);
  stop_topside();
  // The fleet rolled to key 2 while the topside was down; key 1 is gone.
  dccl::Keyring rolled;
  rolled.keys[2].key = std::string(16, 'g');
  rolled.sign_id = 2;
  auto topside_auth = std::make_shared<dccl::MessageAuthenticator>(64, rolled, kTopside);
  topside_codec_.set_authentication(topside_auth, {"qr.Command"});
  start_topside();
  std::vector<Frame> resent = transmit();
  ASSERT_EQ(resent.size(), 1u);
  EXPECT_NE(resent[0].bytes, first[0].bytes);
  EXPECT_EQ(topside_auth->verify(resent[0].bytes, clock_.now_seconds(), kTopside, nullptr), dccl::AuthVerdict::kOk)
      << "sealed again, under the key now signing";
}

TEST_F(AuthResendTest, TheTrailerCountsAgainstTheFrameSoASealedFrameNeverExceedsIt) {
  submit(9);
  const size_t sealed = journal_->load().at(0).sealed.size();
  ASSERT_GT(sealed, 14u) << "DCCL bytes and the 14-byte trailer (64-bit tag)";
  EXPECT_TRUE(transmit(static_cast<uint32_t>(sealed - 1)).empty()) << "one byte short of the sealed message";
  std::vector<Frame> frames = transmit(static_cast<uint32_t>(sealed));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].bytes.size(), sealed);
}

// Two nodes that seal the same Command in the same second (same key, both
// their first seal) send the same stamp; each is a message of its own.
TEST_F(AuthResendTest, TheSameCommandFromTwoNodesInOneSecondIsDeliveredFromEach) {
  dccl::Codec other;
  other.load((dir_.path() / "qr.proto").string());
  other.set_clock([this] { return clock_.now_seconds(); });
  other.set_authentication(std::make_shared<dccl::MessageAuthenticator>(64, fleet_ring(), 3), {"qr.Command"});
  dccl::Codec topside;  // a fresh counter, as the other node's
  topside.load((dir_.path() / "qr.proto").string());
  topside.set_clock([this] { return clock_.now_seconds(); });
  topside.set_authentication(std::make_shared<dccl::MessageAuthenticator>(64, fleet_ring(), kTopside),
                             {"qr.Command"});
  auto m = other.new_message("qr.Command");
  ASSERT_TRUE(pb::TextFormat::ParseFromString("dest: 1 value: 5", m.get()));
  const std::string from_other = other.encode(*m);
  const std::string from_topside = topside.encode(*m);
  EXPECT_EQ(vehicle_->receive(from_topside, kTopside).size(), 1u);
  EXPECT_EQ(vehicle_->receive(from_other, 3).size(), 1u);
  EXPECT_EQ(vehicle_->auth_refusals().replayed, 0u);
  // Each again is a replay; each under the other's id fails its tag.
  EXPECT_TRUE(vehicle_->receive(from_topside, kTopside).empty());
  EXPECT_TRUE(vehicle_->receive(from_other, 3).empty());
  EXPECT_EQ(vehicle_->auth_refusals().replayed, 2u);
  EXPECT_TRUE(vehicle_->receive(from_topside, 3).empty());
  EXPECT_EQ(vehicle_->auth_refusals().auth_failed, 1u);
}

// The must-show's recorded frames, on the simulated clock: a real Command
// recorded and replayed minutes later, and again minutes after the
// vehicle (its store real) was killed and restarted, is refused as
// replayed each time; once older than the window it is refused as stale.
TEST_F(AuthResendTest, RecordedCommandReplayedMinutesLaterAndAfterTheReceiversRestartIsRefused) {
  stop_topside();
  auto m = topside_codec_.new_message("qr.Command");
  ASSERT_TRUE(pb::TextFormat::ParseFromString("dest: 1 value: 11", m.get()));
  const std::string recorded = topside_codec_.encode(*m);
  auto start_vehicle = [this] {
    if (journal_) journal_->flush();
    vehicle_.reset();
    close_store();  // SIGKILL (what the receive committed stays: see stop_topside)
    open_store(dir_.path() / "vehicle");
    vehicle_ = std::make_unique<QueueManager>(vehicle_codec_, queue_config(), kVehicle, clock_, *journal_);
    vehicle_->authenticate("qr.Command", kWindow);
    vehicle_->restore();
  };
  start_vehicle();
  ASSERT_EQ(vehicle_->receive(recorded, kTopside).size(), 1u);
  journal_->flush();
  at(5 * 60);
  EXPECT_TRUE(vehicle_->receive(recorded, kTopside).empty()) << "five minutes later";
  EXPECT_EQ(vehicle_->auth_refusals().replayed, 1u);
  start_vehicle();
  at(9 * 60);
  EXPECT_TRUE(vehicle_->receive(recorded, kTopside).empty()) << "nine minutes later, after the restart";
  EXPECT_EQ(vehicle_->auth_refusals().replayed, 1u);
  at(kWindow + 1);
  EXPECT_TRUE(vehicle_->receive(recorded, kTopside).empty()) << "past the window";
  EXPECT_EQ(vehicle_->auth_refusals().stale, 1u);
  EXPECT_EQ(vehicle_->auth_refusals().auth_failed, 0u);
}

// The guard itself keys what it accepted by sender: were two senders' bytes
// ever the same, the second would not be refused as a replay of the first.
TEST(AuthGuardBySenderTest, TheSameBytesFromAnotherSenderAreNotAReplay) {
  AuthGuard guard;
  guard.add_type("qr.Command", kWindow);
  const dccl::AuthStamp stamp{.key_id = 1, .sent_s = static_cast<uint32_t>(kStart), .counter = 0};
  guard.remember("qr.Command", kTopside, "same bytes", stamp.sent_s, kStart);
  EXPECT_EQ(guard.judge("qr.Command", kTopside, "same bytes", stamp, kStart), AuthRefusal::kReplayed);
  EXPECT_EQ(guard.judge("qr.Command", 3, "same bytes", stamp, kStart), std::nullopt);
  EXPECT_EQ(guard.judge("qr.Command", kTopside, "other bytes", stamp, kStart), std::nullopt);
}

// A store written before senders were told apart (migration 0010, a row in
// auth_accepted without a sender) opened by this build: 0011 keeps the row,
// read back as from any sender, so its bytes stay refused from every node;
// rows written now keep their sender, and the same bytes from two senders
// are two rows.
TEST_F(AuthResendTest, AcceptedRowsOfAStoreAtMigration0010StayValidForEverySender) {
  stop_topside();
  const fs::path old_dir = dir_.path() / "old";
  fs::create_directories(old_dir);
  {
    store::Database db((old_dir / store::kStoreFileName).string());
    std::vector<store::Migration> up_to_10;
    for (const store::Migration& m : store::known_migrations()) {
      if (m.version <= 10) up_to_10.push_back(m);
    }
    ASSERT_EQ(up_to_10.size(), 10u);
    store::migrate(db, up_to_10);
    store::Statement insert =
        db.prepare("INSERT INTO auth_accepted (type, encoded, sent_s) VALUES ('qr.Command', ?, ?)");
    insert.bind_blob(1, "old bytes").bind(2, static_cast<int64_t>(kStart));
    insert.step();
  }
  open_store(old_dir);
  EXPECT_EQ(store_->migration().from_version, 10);
  std::vector<QueueEvent> rows = journal_->authenticated_since(0);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].encoded, "old bytes");
  EXPECT_FALSE(rows[0].auth_sender.has_value()) << "accepted before senders were told apart";

  AuthGuard guard;
  guard.add_type("qr.Command", kWindow);
  guard.refill(*journal_, kStart);
  const dccl::AuthStamp stamp{.key_id = 1, .sent_s = static_cast<uint32_t>(kStart), .counter = 0};
  for (int32_t sender : {kTopside, 3, 17}) {
    EXPECT_EQ(guard.judge("qr.Command", sender, "old bytes", stamp, kStart), AuthRefusal::kReplayed) << sender;
  }

  auto accepted = [](int32_t sender, std::string encoded) {
    QueueEvent e;
    e.kind = QueueEventKind::kReceived;
    e.time = kStart + 1;
    e.type = "qr.Command";
    e.encoded = std::move(encoded);
    e.auth_sent_s = static_cast<uint32_t>(kStart);
    e.auth_sender = sender;
    return e;
  };
  journal_->record(accepted(kTopside, "new bytes"));
  journal_->record(accepted(3, "new bytes"));
  journal_->record(accepted(3, "new bytes"));  // OR IGNORE: one row per sender and bytes
  journal_->flush();
  rows = journal_->authenticated_since(0);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].auth_sender, kTopside);
  EXPECT_EQ(rows[2].auth_sender, 3);
}

}  // namespace
}  // namespace acomms::queue
