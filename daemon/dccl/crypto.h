// Body encryption as DCCL does it: AES-256 in CTR mode, key = SHA-256 of the
// passphrase, initial counter block = first 16 bytes of SHA-256 of the
// cleartext head bytes (id and in_head fields). Only the body is encrypted,
// so the length does not change and there is no tag: it hides content, it
// does not authenticate. CTR is its own inverse, so apply() both encrypts
// and decrypts.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace acomms::dccl {

class BodyCipher {
 public:
  explicit BodyCipher(std::string_view passphrase);

  // XORs body[0, n) with the key stream for this head.
  void apply(std::string_view head, char* body, size_t n) const;

 private:
  std::array<uint8_t, 32> key_{};
};

}  // namespace acomms::dccl
