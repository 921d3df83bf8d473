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
  option (dccl.msg) = { codec_version: 4 id: 40 max_bytes: 16 };
  required int32 dest = 1 [(dccl.field) = { min: 0 max: 30 in_head: true }];
  optional int32 value = 2 [(dccl.field) = { min: 0 max: 1000 }];
}
message Note {
  option (dccl.msg) = { codec_version: 4 id: 41 max_bytes: 16 };
  optional int32 value = 1 [(dccl.field) = { min: 0 max: 1000 }];
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

// The covered bytes are the RFC's 16-byte example 2 when the message is its
// first 10 bytes and the stamp its last 6: key id 0x7e, time 0x17937311
// (little-endian 11 73 93 17), counter 0x2a (the 43rd seal).
TEST(MessageAuthTest, TagIsAesCmacOverMessageAndStampTruncated) {
  MessageAuthenticator auth(64, ring_of(0x7e, kRfcKey));
  std::string scratch;
  for (int i = 0; i < 0x2a; ++i) {
    scratch.clear();
    auth.seal(scratch, 0);
  }
  std::string message = from_hex("6bc1bee22e409f96e93d");
  auth.seal(message, 0x17937311 + 0.9);  // whole seconds: the fraction is dropped
  EXPECT_EQ(to_hex(message), "6bc1bee22e409f96e93d" "7e" "11739317" "2a" "070a16b46b4d4144");
  AuthStamp stamp;
  ASSERT_EQ(auth.verify(message, 0x17937311, &stamp), AuthVerdict::kOk);
  EXPECT_EQ(stamp.key_id, 0x7e);
  EXPECT_EQ(stamp.sent_s, 0x17937311u);
  EXPECT_EQ(stamp.counter, 0x2a);
}

TEST(MessageAuthTest, TrailerIsFortyEightBitsPlusTheTag) {
  for (unsigned bits : {32u, 40u, 48u, 56u, 64u}) {
    MessageAuthenticator auth(bits, ring_of(1, kRfcKey));
    std::string message = "ab";
    auth.seal(message, 1'700'000'000);
    EXPECT_EQ(message.size() * 8, 16 + 48 + bits) << bits;
    EXPECT_EQ(auth.trailer_bytes() * 8, 48 + bits);
    EXPECT_EQ(auth.verify(message, 1'700'000'000, nullptr), AuthVerdict::kOk);
  }
}

TEST(MessageAuthTest, TagLengthOutsideThirtyTwoToSixtyFourOrNotWholeBytesIsRefused) {
  for (unsigned bits : {0u, 24u, 31u, 33u, 72u, 128u}) {
    EXPECT_THAT(error_of([&] { MessageAuthenticator(bits, ring_of(1, kRfcKey)); }),
                HasSubstr("auth.tag_bits " + std::to_string(bits) + ": must be 32 to 64, a multiple of 8"));
  }
}

TEST(MessageAuthTest, KeysOfTheWrongLengthAndSignIdsWithoutKeyAreRefused) {
  EXPECT_THAT(error_of([] { MessageAuthenticator(64, ring_of(3, std::string(15, 'k'))); }),
              HasSubstr("key 3 is 15 bytes: an AES key is 16, 24 or 32 bytes"));
  Keyring ring = ring_of(1, kRfcKey);
  ring.sign_id = 2;
  EXPECT_THAT(error_of([&] { MessageAuthenticator(64, ring); }), HasSubstr("sign 2: no key with that id"));
  EXPECT_THAT(error_of([] { MessageAuthenticator(64, Keyring{}); }), HasSubstr("no key"));
  // A bad reload keeps the keys in use.
  MessageAuthenticator auth(64, ring_of(1, kRfcKey));
  EXPECT_THROW(auth.set_keyring(ring_of(1, "short")), std::invalid_argument);
  std::string message = "x";
  auth.seal(message, 10);
  EXPECT_EQ(auth.verify(message, 10, nullptr), AuthVerdict::kOk);
}

TEST(MessageAuthTest, EveryFlippedBitTruncationUnknownAndRetiredKeyIsRefused) {
  Keyring ring = ring_of(1, kRfcKey);
  ring.keys[2].key = std::string(32, 'n');
  ring.keys[1].accept_until = 1000;
  MessageAuthenticator auth(32, ring);
  std::string message = from_hex("50aa0f");
  auth.seal(message, 900);
  ASSERT_EQ(auth.verify(message, 999, nullptr), AuthVerdict::kOk);
  for (size_t bit = 0; bit < message.size() * 8; ++bit) {
    std::string flipped = message;
    flipped[bit / 8] = static_cast<char>(flipped[bit / 8] ^ (1 << (bit % 8)));
    AuthVerdict v = auth.verify(flipped, 999, nullptr);
    EXPECT_NE(v, AuthVerdict::kOk) << "bit " << bit;
  }
  EXPECT_EQ(auth.verify(message.substr(0, 5), 999, nullptr), AuthVerdict::kTruncated);
  EXPECT_EQ(auth.verify(message, 1001, nullptr), AuthVerdict::kKeyRetired);
  std::string unknown = message;
  unknown[3] = 9;  // the key id
  EXPECT_EQ(auth.verify(unknown, 999, nullptr), AuthVerdict::kUnknownKey);
  // The same message under another key's tag does not verify under key 1.
  MessageAuthenticator other(32, ring_of(1, std::string(16, 'x')));
  std::string forged = from_hex("50aa0f");
  other.seal(forged, 900);
  EXPECT_EQ(auth.verify(forged, 999, nullptr), AuthVerdict::kBadTag);
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
  auto auth = std::make_shared<MessageAuthenticator>(32, ring_of(5, kRfcKey));
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
  auto auth = std::make_shared<MessageAuthenticator>(64, ring_of(1, kRfcKey));
  codec_.set_crypto("fleet passphrase");
  codec_.set_authentication(auth, {"t.Command"});
  const std::string sealed = codec_.encode(*make(codec_, "t.Command", "dest: 3 value: 700"));
  ASSERT_EQ(auth->verify(sealed, 1'700'000'000, nullptr), AuthVerdict::kOk);
  // The body as sent is ciphertext: the tag is over it (encrypt, then tag).
  Codec clear;
  clear.load(dir_.write_proto("b.proto", kProto));
  const std::string plain = clear.encode(*make(clear, "t.Command", "dest: 3 value: 700"));
  EXPECT_NE(sealed.substr(0, plain.size()), plain) << "the body was not encrypted";
  EXPECT_EQ(sealed.substr(0, 2), plain.substr(0, 2)) << "the head stays clear";
  for (size_t byte = 0; byte < plain.size(); ++byte) {
    std::string flipped = sealed;
    flipped[byte] = static_cast<char>(flipped[byte] ^ 0x10);
    EXPECT_EQ(auth->verify(flipped, 1'700'000'000, nullptr), AuthVerdict::kBadTag) << "byte " << byte;
  }
}

TEST_F(AuthenticatedCodecTest, UnloadedOrIdlessTypesCannotBeAuthenticated) {
  auto auth = std::make_shared<MessageAuthenticator>(64, ring_of(1, kRfcKey));
  EXPECT_THAT(error_of([&] { codec_.set_authentication(auth, {"t.Nothing"}); }),
              HasSubstr("authenticated type t.Nothing is not loaded"));
}

}  // namespace
}  // namespace acomms::dccl
