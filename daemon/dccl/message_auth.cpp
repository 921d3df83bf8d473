#include "dccl/message_auth.h"

#include <cryptopp/aes.h>
#include <cryptopp/cmac.h>
#include <cryptopp/misc.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace acomms::dccl {

std::string_view to_string(AuthVerdict verdict) {
  switch (verdict) {
    case AuthVerdict::kOk: return "ok";
    case AuthVerdict::kTruncated: return "truncated trailer";
    case AuthVerdict::kUnknownKey: return "unknown key id";
    case AuthVerdict::kKeyRetired: return "key retired";
    case AuthVerdict::kBadTag: return "tag does not verify";
  }
  return "?";
}

MessageAuthenticator::MessageAuthenticator(unsigned tag_bits, Keyring keyring, int32_t sender)
    : tag_bits_(tag_bits), sender_(sender) {
  if (tag_bits < 32 || tag_bits > 64 || tag_bits % 8 != 0) {
    throw std::invalid_argument("auth.tag_bits " + std::to_string(tag_bits) +
                                ": must be 32 to 64, a multiple of 8");
  }
  set_keyring(std::move(keyring));
}

void MessageAuthenticator::check_keyring(const Keyring& keyring) {
  if (keyring.keys.empty()) throw std::invalid_argument("the keyring holds no key");
  for (const auto& [id, key] : keyring.keys) {
    const size_t n = key.key.size();
    if (n != 16 && n != 24 && n != 32) {
      throw std::invalid_argument("key " + std::to_string(id) + " is " + std::to_string(n) +
                                  " bytes: an AES key is 16, 24 or 32 bytes (32, 48 or 64 hex digits)");
    }
  }
  if (keyring.keys.count(keyring.sign_id) == 0) {
    throw std::invalid_argument("sign " + std::to_string(keyring.sign_id) + ": no key with that id");
  }
}

void MessageAuthenticator::set_keyring(Keyring keyring) {
  check_keyring(keyring);
  auto fresh = std::make_shared<const Keyring>(std::move(keyring));
  std::lock_guard lock(mutex_);
  keyring_ = std::move(fresh);
}

std::shared_ptr<const Keyring> MessageAuthenticator::keyring() const {
  std::lock_guard lock(mutex_);
  return keyring_;
}

std::string MessageAuthenticator::tag(const AuthKey& key, int32_t sender, std::string_view covered) const {
  CryptoPP::CMAC<CryptoPP::AES> cmac(reinterpret_cast<const CryptoPP::byte*>(key.key.data()), key.key.size());
  const auto id = static_cast<uint32_t>(sender);
  const CryptoPP::byte sender_bytes[4] = {static_cast<CryptoPP::byte>(id & 0xff),
                                          static_cast<CryptoPP::byte>((id >> 8) & 0xff),
                                          static_cast<CryptoPP::byte>((id >> 16) & 0xff),
                                          static_cast<CryptoPP::byte>((id >> 24) & 0xff)};
  cmac.Update(sender_bytes, sizeof sender_bytes);
  cmac.Update(reinterpret_cast<const CryptoPP::byte*>(covered.data()), covered.size());
  CryptoPP::byte full[CryptoPP::AES::BLOCKSIZE];
  cmac.Final(full);
  return std::string(reinterpret_cast<const char*>(full), tag_bits_ / 8);
}

void MessageAuthenticator::seal(std::string& message, double now) const {
  std::shared_ptr<const Keyring> ring = keyring();
  const AuthKey& key = ring->keys.at(ring->sign_id);
  // uint32 seconds hold every time until 2106; clamp rather than wrap.
  const double clamped = std::clamp(std::floor(now), 0.0, 4294967295.0);
  const auto sent = static_cast<uint32_t>(clamped);
  const auto counter = static_cast<uint8_t>(counter_.fetch_add(1, std::memory_order_relaxed));
  message.push_back(static_cast<char>(ring->sign_id));
  for (int i = 0; i < 4; ++i) message.push_back(static_cast<char>((sent >> (8 * i)) & 0xff));
  message.push_back(static_cast<char>(counter));
  message += tag(key, sender_, message);
}

AuthVerdict MessageAuthenticator::verify(std::string_view message, double now, int32_t sender,
                                         AuthStamp* stamp) const {
  const size_t trailer = trailer_bytes();
  if (message.size() < trailer) return AuthVerdict::kTruncated;
  const size_t at = message.size() - trailer;
  const auto* p = reinterpret_cast<const uint8_t*>(message.data()) + at;
  AuthStamp s;
  s.key_id = p[0];
  s.sent_s = uint32_t{p[1]} | uint32_t{p[2]} << 8 | uint32_t{p[3]} << 16 | uint32_t{p[4]} << 24;
  s.counter = p[5];
  std::shared_ptr<const Keyring> ring = keyring();
  auto it = ring->keys.find(s.key_id);
  if (it == ring->keys.end()) return AuthVerdict::kUnknownKey;
  if (it->second.accept_until && now > *it->second.accept_until) return AuthVerdict::kKeyRetired;
  const size_t tag_at = at + kStampBytes;
  const std::string expected = tag(it->second, sender, message.substr(0, tag_at));
  // Constant time: the comparison must not tell a forger how many bytes
  // were right.
  if (!CryptoPP::VerifyBufsEqual(reinterpret_cast<const CryptoPP::byte*>(expected.data()),
                                 reinterpret_cast<const CryptoPP::byte*>(message.data() + tag_at),
                                 expected.size())) {
    return AuthVerdict::kBadTag;
  }
  if (stamp) *stamp = s;
  return AuthVerdict::kOk;
}

}  // namespace acomms::dccl
