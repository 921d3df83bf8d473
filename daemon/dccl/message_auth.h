// Authenticated messages: an extension of DCCL that makes a forged, altered
// or replayed message recognisable.
//
// Problem: DCCL's encryption (crypto.h) hides a body but authenticates
// nothing: a flipped ciphertext bit decodes to another valid message, and a
// recorded message replays. Anyone with a compatible modem could command a
// vehicle. Decision: a type marked authenticated carries, after its DCCL
// bytes (head and body, body encrypted when crypto is on), a trailer
//
//   byte 0      key id (0..255): which fleet key made the tag
//   bytes 1-4   send time, Unix seconds, uint32 little-endian
//   byte 5      counter: messages this process sealed, mod 256, so that two
//               identical messages in one second still differ
//   bytes 6..   tag: the first tag_bits/8 bytes (4 to 8) of AES-CMAC under
//               the key, over the sender's node id (4 bytes, uint32
//               little-endian; not sent) and everything before the tag
//               (head, body as sent, key id, time, counter): encrypt, then
//               tag
//
// so the cost is 48 + tag_bits bits (80 to 112) per message. The trailer
// is a fixed length, so messages still concatenate without lengths.
// The sender's id is covered but not sent: the receiver takes it from the
// transmission (its link source), so that two nodes sealing the same
// message in the same second are told apart at no cost in bits, and a
// recorded message sent again under another node's id does not verify (a
// replay cannot pass as new by changing its source). A node seals with
// the one id it transmits under (every link's modem_id is the node's).
// Deciding whether the stamp is fresh (window, replay) needs memory of what
// was accepted, and that lives in the queue (queue/auth_guard.h): this
// class only seals and checks tags.
//
// Keys come in a Keyring (one id each, an optional time after which the key
// is no longer accepted, and the one id that seals): a fleet rolls to a new
// key by adding it, moving `sign` to it, and giving the old one an `until`.
//
// Thread safety: every member may be called from any thread; the keyring
// is replaced whole (set_keyring, on SIGHUP) and each call uses the one it
// found when it started.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace acomms::dccl {

struct AuthKey {
  std::string key;  // raw AES key bytes: 16, 24 or 32
  // Unix seconds after which messages under this key are refused; nullopt:
  // accepted as long as it is in the keyring.
  std::optional<double> accept_until;
};

struct Keyring {
  std::map<uint8_t, AuthKey> keys;
  uint8_t sign_id = 0;  // must be in keys
};

// What a trailer says, once its tag verified.
struct AuthStamp {
  uint8_t key_id = 0;
  uint32_t sent_s = 0;  // Unix seconds
  uint8_t counter = 0;
};

enum class AuthVerdict {
  kOk,
  kTruncated,   // fewer bytes than a trailer
  kUnknownKey,  // key id not in the keyring
  kKeyRetired,  // key past its accept_until
  kBadTag,      // the tag does not verify
};
std::string_view to_string(AuthVerdict verdict);

class MessageAuthenticator {
 public:
  static constexpr size_t kStampBytes = 6;  // key id, time, counter
  // `sender`: the node id this process seals as (its modem id). Throws
  // std::invalid_argument unless 32 <= tag_bits <= 64 and a multiple of 8,
  // or when the keyring breaks its rules (check_keyring).
  MessageAuthenticator(unsigned tag_bits, Keyring keyring, int32_t sender);

  // Throws std::invalid_argument naming the problem: no keys, a key of a
  // length AES does not take, a sign id that is not in the keyring.
  static void check_keyring(const Keyring& keyring);

  // Replaces the keys (SIGHUP). Throws as check_keyring; then keeps the old.
  void set_keyring(Keyring keyring);
  std::shared_ptr<const Keyring> keyring() const;

  unsigned tag_bits() const { return tag_bits_; }
  int32_t sender() const { return sender_; }
  size_t trailer_bytes() const { return kStampBytes + tag_bits_ / 8; }

  // Appends the trailer to `message` (its DCCL bytes as sent), stamped
  // `now` (Unix seconds) with the sign key, as sent by sender().
  void seal(std::string& message, double now) const;

  // Checks the trailer at the end of `message` (DCCL bytes then trailer)
  // at `now`, as sent by node `sender` (the transmission's source); on kOk
  // fills *stamp.
  AuthVerdict verify(std::string_view message, double now, int32_t sender, AuthStamp* stamp) const;

 private:
  std::string tag(const AuthKey& key, int32_t sender, std::string_view covered) const;

  unsigned tag_bits_;
  int32_t sender_;
  mutable std::mutex mutex_;  // guards keyring_ (the pointer, not the keys)
  std::shared_ptr<const Keyring> keyring_;
  mutable std::atomic<uint32_t> counter_{0};
};

}  // namespace acomms::dccl
