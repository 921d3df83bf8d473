// "Nobody commands a vehicle they should not" at the queue's receive side,
// on the simulated clock: a message of an authenticated type reaches the
// caller only with a tag that verifies, a stamp inside its window and bytes
// never accepted before (also after a restart over the same journal); each
// refusal is counted under its reason and logged once per burst.

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include "dccl/message_auth.h"
#include "queue_manager_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package qa;
message Command {
  option (dccl.msg) = { codec_version: 4 id: 5 max_bytes: 32 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
message Note {
  option (dccl.msg) = { codec_version: 4 id: 6 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

using testing::kOwnId;
using testing::kStart;

constexpr int32_t kPeer = 4;
constexpr double kWindow = 600;

dccl::Keyring ring(std::initializer_list<std::pair<uint8_t, char>> keys, uint8_t sign,
                   std::optional<double> old_until = std::nullopt) {
  dccl::Keyring r;
  for (auto [id, fill] : keys) r.keys[id].key = std::string(16, fill);
  if (old_until) r.keys.begin()->second.accept_until = old_until;
  r.sign_id = sign;
  return r;
}

class AuthGuardTest : public testing::QueueManagerFixture {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("acomms-queue-auth-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::ofstream(dir_ / "qa.proto") << kProto;
    for (dccl::Codec* codec : {&codec_, &sender_, &rogue_}) {
      codec->load((dir_ / "qa.proto").string());
      codec->set_clock([this] { return clock_.now_seconds(); });
    }
    receiver_auth_ = std::make_shared<dccl::MessageAuthenticator>(64, ring({{1, 'a'}}, 1), kOwnId);
    codec_.set_authentication(receiver_auth_, {"qa.Command"});
    sender_.set_authentication(std::make_shared<dccl::MessageAuthenticator>(64, ring({{1, 'a'}}, 1), kPeer),
                               {"qa.Command"});
    // Knows the format and the key id, not the key.
    rogue_.set_authentication(std::make_shared<dccl::MessageAuthenticator>(64, ring({{1, 'r'}}, 1), kPeer),
                              {"qa.Command"});
    make();
  }
  void TearDown() override { fs::remove_all(dir_); }

  QueueManager& make() {
    v1::QueueConfig config;
    for (const char* type : {"qa.Command", "qa.Note"}) {
      v1::QueueTypeConfig* entry = config.add_type();
      entry->set_type(type);
      entry->mutable_roles()->set_source_field("src");
      entry->mutable_roles()->set_destination_field("dest");
    }
    config.mutable_defaults()->set_ttl_s(300);
    config.set_duplicate_window_s(3600);  // so that the authenticated window bounds a Submit's ttl
    QueueManager& manager = install(std::make_unique<QueueManager>(codec_, config, kOwnId, clock_, journal_));
    manager.authenticate("qa.Command", kWindow);
    manager.restore();
    return manager;
  }

  std::string command(dccl::Codec& from, int value) {
    auto m = from.new_message("qa.Command");
    EXPECT_TRUE(pb::TextFormat::ParseFromString("src: 4 dest: 1 value: " + std::to_string(value), m.get()));
    return from.encode(*m);
  }
  size_t delivered(const std::string& frame) { return manager_->receive(frame, kPeer).size(); }
  const AuthRefusals& refused() { return manager_->auth_refusals(); }

  dccl::Codec sender_;
  dccl::Codec rogue_;
  std::shared_ptr<dccl::MessageAuthenticator> receiver_auth_;
};

TEST_F(AuthGuardTest, RealCommandArrivesOnceAndItsCopyIsRefusedAsReplayed) {
  const std::string real = command(sender_, 7);
  auto first = manager_->receive(real, kPeer);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].message->ShortDebugString(), "src: 4 dest: 1 value: 7");
  at(30);
  EXPECT_EQ(delivered(real), 0u);
  EXPECT_EQ(refused().replayed, 1u);
  EXPECT_EQ(refused().auth_failed + refused().stale, 0u);
  // Two identical Commands sealed in the same second still differ (counter).
  const std::string again = command(sender_, 7);
  EXPECT_NE(again, real);
  EXPECT_EQ(delivered(again), 1u);
}

TEST_F(AuthGuardTest, ForgedAndBitFlippedCommandsAreRefusedAsAuthFailed) {
  EXPECT_EQ(delivered(command(rogue_, 9)), 0u) << "forged with the wrong key";
  const std::string real = command(sender_, 7);
  for (size_t bit = 0; bit < real.size() * 8; ++bit) {
    std::string flipped = real;
    flipped[bit / 8] = static_cast<char>(flipped[bit / 8] ^ (1 << (bit % 8)));
    EXPECT_EQ(delivered(flipped), 0u) << "bit " << bit;
  }
  // No key at all: a plain DCCL Command without the trailer.
  dccl::Codec keyless;
  keyless.load((dir_ / "qa.proto").string());
  auto m = keyless.new_message("qa.Command");
  ASSERT_TRUE(pb::TextFormat::ParseFromString("src: 4 dest: 1 value: 9", m.get()));
  EXPECT_EQ(delivered(keyless.encode(*m)), 0u) << "no trailer";
  // Every bit of the id byte leads elsewhere (unknown ids are malformed); the
  // rest are auth failures, plus the forged and the keyless.
  EXPECT_GE(refused().auth_failed, real.size() * 8 - 8 + 2);
  EXPECT_EQ(refused().replayed + refused().stale, 0u);
  EXPECT_EQ(delivered(real), 1u) << "the real one still arrives";
}

TEST_F(AuthGuardTest, CommandOlderOrNewerThanTheWindowIsRefusedAsStale) {
  const std::string old = command(sender_, 1);
  at(kWindow + 1);
  EXPECT_EQ(delivered(old), 0u);
  EXPECT_EQ(refused().stale, 1u);
  const std::string ahead = command(sender_, 2);  // stamped at kWindow + 1
  at(-1);
  EXPECT_EQ(delivered(ahead), 0u);
  EXPECT_EQ(refused().stale, 2u);
  at(kWindow);
  EXPECT_EQ(delivered(command(sender_, 3)), 1u);
}

TEST_F(AuthGuardTest, ReplayAfterTheReceiversRestartIsStillRefused) {
  const std::string real = command(sender_, 7);
  ASSERT_EQ(delivered(real), 1u);
  at(100);
  make();  // a new manager over the same journal: the restart
  EXPECT_EQ(delivered(real), 0u);
  EXPECT_EQ(refused().replayed, 1u);
  // The stamp is in the store with the received event.
  size_t stamped = 0;
  for (const QueueEvent& e : journal_.events()) stamped += e.auth_sent_s.has_value();
  EXPECT_EQ(stamped, 1u);
  at(kWindow + 1);
  make();
  EXPECT_EQ(delivered(real), 0u);
  EXPECT_EQ(refused().stale, 1u) << "forgotten by then, but older than the window";
}

TEST_F(AuthGuardTest, KeyRollAcceptsBothKeysUntilTheOldOnesTimeThenOnlyTheNew) {
  // The fleet moves to key 2; key 1 is accepted until kStart + 100.
  receiver_auth_->set_keyring(ring({{1, 'a'}, {2, 'b'}}, 2, kStart + 100));
  dccl::Codec late;  // a vehicle still signing with key 1
  late.load((dir_ / "qa.proto").string());
  late.set_clock([this] { return clock_.now_seconds(); });
  late.set_authentication(std::make_shared<dccl::MessageAuthenticator>(64, ring({{1, 'a'}}, 1), kPeer), {"qa.Command"});
  sender_.set_authentication(std::make_shared<dccl::MessageAuthenticator>(64, ring({{2, 'b'}}, 2), kPeer),
                             {"qa.Command"});
  at(50);
  EXPECT_EQ(delivered(command(late, 1)), 1u) << "old key inside the overlap";
  EXPECT_EQ(delivered(command(sender_, 2)), 1u) << "new key";
  at(101);
  EXPECT_EQ(delivered(command(late, 3)), 0u) << "old key after its time";
  EXPECT_EQ(refused().auth_failed, 1u);
  EXPECT_EQ(delivered(command(sender_, 4)), 1u);
}

TEST_F(AuthGuardTest, UnmarkedTypesAreUntouched) {
  auto note = codec_.new_message("qa.Note");
  ASSERT_TRUE(pb::TextFormat::ParseFromString("src: 4 dest: 1 value: 5", note.get()));
  dccl::Codec plain;
  plain.load((dir_ / "qa.proto").string());
  EXPECT_EQ(codec_.encode(*note), plain.encode(*note));
  EXPECT_EQ(delivered(plain.encode(*note)), 1u);
}

TEST_F(AuthGuardTest, RefusalsAreLoggedOncePerBurst) {
  std::ostringstream log;
  auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(log);
  auto previous = spdlog::default_logger();
  spdlog::set_default_logger(std::make_shared<spdlog::logger>("auth-test", sink));
  for (int i = 0; i < 50; ++i) {
    at(i);
    delivered(command(rogue_, i));
  }
  at(49 + AuthGuard::kBurstGapS + 1);
  delivered(command(rogue_, 1));
  spdlog::set_default_logger(previous);
  const std::string text = log.str();
  size_t lines = 0;
  for (size_t pos = text.find("auth: qa.Command"); pos != std::string::npos;
       pos = text.find("auth: qa.Command", pos + 1)) {
    ++lines;
  }
  EXPECT_EQ(lines, 2u) << text;
  EXPECT_NE(text.find("auth_failed: tag does not verify"), std::string::npos) << text;
  EXPECT_NE(text.find("49 more in the previous burst"), std::string::npos) << text;
  EXPECT_EQ(refused().auth_failed, 51u);
}

TEST_F(AuthGuardTest, WindowOfZeroOrShorterThanTheTtlAndLongSubmitsAreRefused) {
  v1::QueueConfig config;
  config.mutable_defaults()->set_ttl_s(300);
  QueueManager other(codec_, config, kOwnId, clock_, journal_);
  EXPECT_THROW(other.authenticate("qa.Command", 0), std::invalid_argument);
  EXPECT_THROW(other.authenticate("qa.Command", 200), std::invalid_argument);
  EXPECT_THROW(other.authenticate("qa.Note", 600), std::invalid_argument) << "the codec does not authenticate it";
  SubmitResult result = submit_result("qa.Command", "src: 1 dest: 4 value: 3", kWindow + 1);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.text.find("auth.type.window_s"), std::string::npos) << result.text;
  EXPECT_GT(submit("qa.Command", "src: 1 dest: 4 value: 3", kWindow), 0);
}

}  // namespace
}  // namespace acomms::queue
