// The authenticated-message trailer (dccl/message_auth.h) on bytes: its
// layout and length, the AES-CMAC tag against RFC 4493's vector, encrypt
// then tag, and that a type not marked stays byte-identical to DCCL 4.
#include "dccl/message_auth.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dccl/codec.h"
#include "test_util.h"

namespace acomms::dccl {
namespace {

using ::testing::HasSubstr;
using testing::from_hex;
using testing::make;
using testing::to_hex;

constexpr const char* kProto = R"(
message Command {
  option (dccl.msg) = { codec_version: 4 id: 40 max_bytes: 32 };
  required int32 dest = 1 [(dccl.field) = { min: 0 max: 30 in_head: true }];
  optional int32 value = 2 [(dccl.field) = { min: 0 max: 1000 }];
}
message Note {
  option (dccl.msg) = { codec_version: 4 id: 41 max_bytes: 16 };
  optional int32 value = 1 [(dccl.field) = { min: 0 max: 1000 }];
}
message Tight {
  option (dccl.msg) = { codec_version: 4 id: 42 max_bytes: 17 };
  required int32 dest = 1 [(dccl.field) = { min: 0 max: 30 in_head: true }];
  optional int32 value = 2 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

// RFC 4493's AES-128 key.
const std::string kRfcKey = from_hex("2b7e151628aed2a6abf7158809cf4f3c");

Keyring ring_of(uint8_t id, const std::string& key) {
  Keyring ring;
  ring.keys[id].key = key;
  ring.sign_id = id;
  return ring;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// The covered bytes are the RFC's 16-byte example 2 when the sender's id is
// its first 4 bytes (little-endian 0xe2bec16b; covered, not sent), the
// message the next 6 and the stamp its last 6: key id 0x7e, time 0x17937311
// (little-endian 11 73 93 17), counter 0x2a (the 43rd seal).
constexpr int32_t kRfcSender = static_cast<int32_t>(0xe2bec16bu);

TEST(MessageAuthTest, TagIsAesCmacOverSenderMessageAndStampTruncated) {
  MessageAuthenticator auth(64, ring_of(0x7e, kRfcKey), kRfcSender);
  std::string scratch;
  for (int i = 0; i < 0x2a; ++i) {
    scratch.clear();
    auth.seal(scratch, 0);
  }
  std::string message = from_hex("2e409f96e93d");
  auth.seal(message, 0x17937311 + 0.9);  // whole seconds: the fraction is dropped
  EXPECT_EQ(to_hex(message), "2e409f96e93d" "7e" "11739317" "2a" "070a16b46b4d4144");
  AuthStamp stamp;
  ASSERT_EQ(auth.verify(message, 0x17937311, kRfcSender, &stamp), AuthVerdict::kOk);
  EXPECT_EQ(stamp.key_id, 0x7e);
  EXPECT_EQ(stamp.sent_s, 0x17937311u);
  EXPECT_EQ(stamp.counter, 0x2a);
}

// Two nodes sealing the same message in the same second (same key, same
// counter) make the same bytes; each verifies only as from its own sender,
// so a copy sent again under another node's id is not taken for new.
TEST(MessageAuthTest, TagBindsTheSenderSoTheSameBytesFromAnotherNodeDoNotVerify) {
  MessageAuthenticator node2(64, ring_of(1, kRfcKey), 2);
  MessageAuthenticator node3(64, ring_of(1, kRfcKey), 3);
  std::string from2 = "cmd";
  std::string from3 = "cmd";
  node2.seal(from2, 1'700'000'000);
  node3.seal(from3, 1'700'000'000);
  EXPECT_NE(from2, from3) << "the tag differs with the sender";
  EXPECT_EQ(from2.substr(0, from2.size() - 8), from3.substr(0, from3.size() - 8)) << "the rest is the same";
  EXPECT_EQ(node2.verify(from2, 1'700'000'000, 2, nullptr), AuthVerdict::kOk);
  EXPECT_EQ(node2.verify(from2, 1'700'000'000, 3, nullptr), AuthVerdict::kBadTag);
  EXPECT_EQ(node2.verify(from3, 1'700'000'000, 3, nullptr), AuthVerdict::kOk);
  EXPECT_EQ(node2.verify(from3, 1'700'000'000, 2, nullptr), AuthVerdict::kBadTag);
}

TEST(MessageAuthTest, TrailerIsFortyEightBitsPlusTheTag) {
  for (unsigned bits : {32u, 40u, 48u, 56u, 64u}) {
    MessageAuthenticator auth(bits, ring_of(1, kRfcKey), 3);
    std::string message = "ab";
    auth.seal(message, 1'700'000'000);
    EXPECT_EQ(message.size() * 8, 16 + 48 + bits) << bits;
    EXPECT_EQ(auth.trailer_bytes() * 8, 48 + bits);
    EXPECT_EQ(auth.verify(message, 1'700'000'000, 3, nullptr), AuthVerdict::kOk);
  }
}

TEST(MessageAuthTest, TagLengthOutsideThirtyTwoToSixtyFourOrNotWholeBytesIsRefused) {
  for (unsigned bits : {0u, 24u, 31u, 33u, 72u, 128u}) {
    EXPECT_THAT(error_of([&] { MessageAuthenticator(bits, ring_of(1, kRfcKey), 3); }),
                HasSubstr("auth.tag_bits " + std::to_string(bits) + ": must be 32 to 64, a multiple of 8"));
  }
}

TEST(MessageAuthTest, KeysOfTheWrongLengthAndSignIdsWithoutKeyAreRefused) {
  EXPECT_THAT(error_of([] { MessageAuthenticator(64, ring_of(3, std::string(15, 'k')), 3); }),
              HasSubstr("key 3 is 15 bytes: an AES key is 16, 24 or 32 bytes"));
  Keyring ring = ring_of(1, kRfcKey);
  ring.sign_id = 2;
  EXPECT_THAT(error_of([&] { MessageAuthenticator(64, ring, 3); }), HasSubstr("sign 2: no key with that id"));
  EXPECT_THAT(error_of([] { MessageAuthenticator(64, Keyring{}, 3); }), HasSubstr("no key"));
  // A bad reload keeps the keys in use.
  MessageAuthenticator auth(64, ring_of(1, kRfcKey), 3);
  EXPECT_THROW(auth.set_keyring(ring_of(1, "short")), std::invalid_argument);
  std::string message = "x";
  auth.seal(message, 10);
  EXPECT_EQ(auth.verify(message, 10, 3, nullptr), AuthVerdict::kOk);
}

TEST(MessageAuthTest, EveryFlippedBitTruncationUnknownAndRetiredKeyIsRefused) {
  Keyring ring = ring_of(1, kRfcKey);
  ring.keys[2].key = std::string(32, 'n');
  ring.keys[1].accept_until = 1000;
  MessageAuthenticator auth(32, ring, 3);
  std::string message = from_hex("50aa0f");
  auth.seal(message, 900);
  ASSERT_EQ(auth.verify(message, 999, 3, nullptr), AuthVerdict::kOk);
  for (size_t bit = 0; bit < message.size() * 8; ++bit) {
    std::string flipped = message;
    flipped[bit / 8] = static_cast<char>(flipped[bit / 8] ^ (1 << (bit % 8)));
    AuthVerdict v = auth.verify(flipped, 999, 3, nullptr);
    EXPECT_NE(v, AuthVerdict::kOk) << "bit " << bit;
  }
  EXPECT_EQ(auth.verify(message.substr(0, 5), 999, 3, nullptr), AuthVerdict::kTruncated);
  EXPECT_EQ(auth.verify(message, 1001, 3, nullptr), AuthVerdict::kKeyRetired);
  std::string unknown = message;
  unknown[3] = 9;  // the key id
  EXPECT_EQ(auth.verify(unknown, 999, 3, nullptr), AuthVerdict::kUnknownKey);
  // The same message under another key's tag does not verify under key 1.
  MessageAuthenticator other(32, ring_of(1, std::string(16, 'x')), 3);
  std::string forged = from_hex("50aa0f");
  other.seal(forged, 900);
  EXPECT_EQ(auth.verify(forged, 999, 3, nullptr), AuthVerdict::kBadTag);
}

class AuthenticatedCodecTest : public ::testing::Test {
 protected:
  void SetUp() override {
    codec_.load(dir_.write_proto("a.proto", kProto));
    codec_.set_clock([] { return 1'700'000'000.0; });
  }
  testing::TempDir dir_;
  Codec codec_;
};

TEST_F(AuthenticatedCodecTest, UnmarkedTypeStaysByteIdenticalAndMarkedTypeGainsTheTrailer) {
  const std::string note_before = codec_.encode(*make(codec_, "t.Note", "value: 7"));
  const std::string command_before = codec_.encode(*make(codec_, "t.Command", "dest: 3 value: 7"));
  auto auth = std::make_shared<MessageAuthenticator>(32, ring_of(5, kRfcKey), 3);
  codec_.set_authentication(auth, {"t.Command"});
  EXPECT_EQ(codec_.encode(*make(codec_, "t.Note", "value: 7")), note_before);
  const std::string command = codec_.encode(*make(codec_, "t.Command", "dest: 3 value: 7"));
  ASSERT_EQ(command.size(), command_before.size() + 10);
  EXPECT_EQ(command.substr(0, command_before.size()), command_before);
  EXPECT_EQ(to_hex(command.substr(command_before.size(), 6)), "05" "00f15365" "00");  // key 5, 1700000000 LE
  EXPECT_TRUE(codec_.authenticated("t.Command"));
  EXPECT_FALSE(codec_.authenticated("t.Note"));
  // Decoding consumes the trailer, so messages still concatenate.
  auto all = codec_.decode(command + note_before + command);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[2]->ShortDebugString(), "dest: 3 value: 7");
  // Ending inside the trailer is an error naming it.
  EXPECT_THAT(error_of([&] { codec_.decode(command.substr(0, command.size() - 1)); }),
              HasSubstr("t.Command: authentication trailer truncated (9 of 10 bytes)"));
}

TEST_F(AuthenticatedCodecTest, TagCoversTheCiphertextAndTheCleartextHead) {
  auto auth = std::make_shared<MessageAuthenticator>(64, ring_of(1, kRfcKey), 3);
  codec_.set_crypto("fleet passphrase");
  codec_.set_authentication(auth, {"t.Command"});
  const std::string sealed = codec_.encode(*make(codec_, "t.Command", "dest: 3 value: 700"));
  ASSERT_EQ(auth->verify(sealed, 1'700'000'000, 3, nullptr), AuthVerdict::kOk);
  // The body as sent is ciphertext: the tag is over it (encrypt, then tag).
  Codec clear;
  clear.load(dir_.write_proto("b.proto", kProto));
  const std::string plain = clear.encode(*make(clear, "t.Command", "dest: 3 value: 700"));
  EXPECT_NE(sealed.substr(0, plain.size()), plain) << "the body was not encrypted";
  EXPECT_EQ(sealed.substr(0, 2), plain.substr(0, 2)) << "the head stays clear";
  for (size_t byte = 0; byte < plain.size(); ++byte) {
    std::string flipped = sealed;
    flipped[byte] = static_cast<char>(flipped[byte] ^ 0x10);
    EXPECT_EQ(auth->verify(flipped, 1'700'000'000, 3, nullptr), AuthVerdict::kBadTag) << "byte " << byte;
  }
}

TEST_F(AuthenticatedCodecTest, UnloadedOrIdlessTypesCannotBeAuthenticated) {
  auto auth = std::make_shared<MessageAuthenticator>(64, ring_of(1, kRfcKey), 3);
  EXPECT_THAT(error_of([&] { codec_.set_authentication(auth, {"t.Nothing"}); }),
              HasSubstr("authenticated type t.Nothing is not loaded"));
}

// max_bytes is the frame the type was sized for: its largest message, sealed,
// must fit it. t.Tight is up to 4 DCCL bytes: with a 64-bit tag (14 trailer
// bytes) that is 18, one more than its max_bytes 17; a 56-bit tag fits.
TEST_F(AuthenticatedCodecTest, TypeWhoseSealedMessageCanExceedItsMaxBytesIsRefused) {
  auto long_tags = std::make_shared<MessageAuthenticator>(64, ring_of(1, kRfcKey), 3);
  EXPECT_THAT(error_of([&] { codec_.set_authentication(long_tags, {"t.Command", "t.Tight"}); }),
              HasSubstr("authenticated type t.Tight is up to 18 bytes sealed (4 DCCL + 14 trailer at 64-bit tags), "
                        "more than its max_bytes 17: raise max_bytes or shorten auth.tag_bits"));
  EXPECT_FALSE(codec_.authenticated("t.Command")) << "all or nothing";
  auto shorter = std::make_shared<MessageAuthenticator>(56, ring_of(1, kRfcKey), 3);
  codec_.set_authentication(shorter, {"t.Tight"});
  const std::string sealed = codec_.encode(*make(codec_, "t.Tight", "dest: 30 value: 1000"));
  EXPECT_EQ(sealed.size(), 17u) << "the largest message, sealed, fills max_bytes exactly";
}

}  // namespace
}  // namespace acomms::dccl
