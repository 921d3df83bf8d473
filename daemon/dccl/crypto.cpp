#include "dccl/crypto.h"

#include <cryptopp/aes.h>
#include <cryptopp/modes.h>
#include <cryptopp/sha.h>

namespace acomms::dccl {

BodyCipher::BodyCipher(std::string_view passphrase) {
  CryptoPP::SHA256().CalculateDigest(key_.data(), reinterpret_cast<const CryptoPP::byte*>(passphrase.data()),
                                     passphrase.size());
}

void BodyCipher::apply(std::string_view head, char* body, size_t n) const {
  if (n == 0) return;
  CryptoPP::byte digest[CryptoPP::SHA256::DIGESTSIZE];
  CryptoPP::SHA256().CalculateDigest(digest, reinterpret_cast<const CryptoPP::byte*>(head.data()), head.size());
  // Crypto++'s CTR mode increments the whole 128-bit block big-endian, as
  // the reference does.
  CryptoPP::CTR_Mode<CryptoPP::AES>::Encryption ctr;
  ctr.SetKeyWithIV(key_.data(), key_.size(), digest, CryptoPP::AES::BLOCKSIZE);
  auto* p = reinterpret_cast<CryptoPP::byte*>(body);
  ctr.ProcessData(p, p, n);
}

}  // namespace acomms::dccl
