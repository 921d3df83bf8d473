// libFuzzer target: the receipts a gateway hears (route/custody_receipt.h,
// route/receipt_seal.h), which any node in range can put on the water.
//
// Three ways in, each input through all of them:
//  1. The bytes as a received frame's rest, walked the way the forwarder
//     walks it (Forwarder::on_envelope, on_custody_receipt): custody
//     receipts back to back, each followed by its seal when the node has
//     an authenticator. A receipt that decodes encodes back to its own 7
//     bytes; a refusal of its seal says why and consumes exactly the
//     seal's bytes (or what is left); a start that decodes as an envelope
//     is never taken for a custody receipt (byte 2 tells them apart).
//  2. The bytes as a delivered envelope's payload: an end-to-end receipt
//     and its seal (Forwarder::deliver_here).
//  3. The bytes as a recipe: receipts sealed with the fleet's real key at
//     times the input picks, back to back, then (maybe) one bit flipped.
//     Each receipt before the flip must decode to what was sealed and its
//     seal pass exactly when its time is inside the window; the one whose
//     bytes the flip touched must not pass (the tag covers every byte).
// Anything else (a crash, a sanitizer report, a trap) is a bug.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dccl/message_auth.h"
#include "route/custody_receipt.h"
#include "route/envelope.h"
#include "route/receipt.h"
#include "route/receipt_seal.h"

namespace {

using namespace acomms::route;
using acomms::dccl::AuthVerdict;
using acomms::dccl::MessageAuthenticator;

constexpr double kNow = 1'700'000'000.0;
constexpr int32_t kSender = 7;     // the transmission's source (custody) or the envelope's origin (end to end)
constexpr double kWindowS = 600;   // the custody ttl the forwarder passes
constexpr double kSkewS = 60;      // receipt_seal.cpp's clock skew, either way

std::shared_ptr<MessageAuthenticator> make_auth() {
  acomms::dccl::Keyring ring;
  ring.keys[1].key = std::string(16, 'k');
  ring.keys[2].key = std::string(32, 'K');
  ring.keys[2].accept_until = kNow - 1;  // retired
  ring.sign_id = 1;
  return std::make_shared<MessageAuthenticator>(40, ring, kSender);
}

// 1: a frame's rest, as the forwarder walks it.
void walk_frame(std::string_view rest, uint32_t id, const MessageAuthenticator* auth) {
  const size_t want = sealed_size(kCustodyReceiptBytes, auth);
  while (!rest.empty()) {
    if (!starts_custody_receipt(rest, id)) return;  // an envelope, or nothing: not this target's
    size_t used = 0;
    std::string error;
    if (decode_envelope(rest, id, &used, &error)) __builtin_trap();  // both at once: the dispatch is ambiguous
    std::optional<CustodyReceipt> receipt = decode_custody_receipt(rest, id);
    if (!receipt) {
      if (rest.size() >= kCustodyReceiptBytes) __builtin_trap();  // whole, and starts like one
      return;
    }
    if (encode_custody_receipt(*receipt, id) != rest.substr(0, kCustodyReceiptBytes)) __builtin_trap();
    const SealCheck seal = check_receipt_seal(rest, kCustodyReceiptBytes, auth, kSender, kNow, kWindowS);
    if (seal.used != std::min(want, rest.size()) || seal.used < kCustodyReceiptBytes) __builtin_trap();
    if (!seal.ok && seal.why.empty()) __builtin_trap();
    if (auth == nullptr && !seal.ok) __builtin_trap();
    // A seal that passed was made for this sender and no other.
    if (seal.ok && auth != nullptr &&
        auth->verify(rest.substr(0, want), kNow, kSender + 1, nullptr) == AuthVerdict::kOk) {
      __builtin_trap();
    }
    rest.remove_prefix(seal.used);
  }
}

// 2: a delivered envelope's payload that starts like a receipt.
void check_payload(std::string_view payload, uint32_t id, const MessageAuthenticator* auth) {
  const SealCheck seal = check_receipt_seal(payload, kReceiptBytes, auth, kSender, kNow, kWindowS);
  if (seal.used != std::min(sealed_size(kReceiptBytes, auth), payload.size())) __builtin_trap();
  if (!seal.ok && seal.why.empty()) __builtin_trap();
  if (!seal.ok || seal.used != payload.size()) return;
  std::optional<Receipt> receipt = decode_receipt(payload.substr(0, kReceiptBytes), id);
  if (receipt && encode_receipt(*receipt, id) != payload.substr(0, kReceiptBytes)) __builtin_trap();
}

// 3: receipts sealed for real, from 7-byte records (verdict bit, origin,
// seq, signed send-time offset in seconds); a leftover byte picks a bit to
// flip in the frame.
void check_sealed(std::string_view recipe, uint32_t id, const MessageAuthenticator& auth) {
  constexpr size_t kRecord = 7;
  const auto* b = reinterpret_cast<const unsigned char*>(recipe.data());
  struct Sealed {
    CustodyReceipt receipt;
    double sent_s;
    size_t at;
  };
  std::vector<Sealed> sealed;
  std::string frame;
  for (size_t i = 0; i + kRecord <= recipe.size() && sealed.size() < 16; i += kRecord) {
    Sealed s;
    s.receipt.verdict = (b[i] & 1) != 0 ? CustodyVerdict::kRefused : CustodyVerdict::kTaken;
    s.receipt.about.origin = static_cast<uint16_t>(b[i + 1] | b[i + 2] << 8);
    s.receipt.about.seq = static_cast<uint16_t>(b[i + 3] | b[i + 4] << 8);
    s.sent_s = kNow + static_cast<int16_t>(static_cast<uint16_t>(b[i + 5] | b[i + 6] << 8));
    s.at = frame.size();
    std::string bytes = encode_custody_receipt(s.receipt, id);
    seal_receipt(bytes, &auth, s.sent_s);
    if (bytes.size() != sealed_size(kCustodyReceiptBytes, &auth)) __builtin_trap();
    frame += bytes;
    sealed.push_back(s);
  }
  if (sealed.empty()) return;
  std::optional<size_t> flipped;
  if (recipe.size() % kRecord != 0) {
    const size_t bit = (static_cast<size_t>(b[recipe.size() - 1]) * 131) % (frame.size() * 8);
    frame[bit / 8] = static_cast<char>(frame[bit / 8] ^ (1 << (bit % 8)));
    flipped = bit / 8;
  }
  const size_t each = sealed_size(kCustodyReceiptBytes, &auth);
  std::string_view rest = frame;
  for (const Sealed& s : sealed) {
    const bool touched = flipped && *flipped >= s.at && *flipped < s.at + each;
    std::optional<CustodyReceipt> receipt = decode_custody_receipt(rest, id);
    if (!receipt) {
      if (!touched) __builtin_trap();
      return;  // the flip made it something else: the walk ends here
    }
    if (!touched && !(*receipt == s.receipt)) __builtin_trap();
    const SealCheck seal = check_receipt_seal(rest, kCustodyReceiptBytes, &auth, kSender, kNow, kWindowS);
    if (seal.used != each) __builtin_trap();
    const bool fresh = s.sent_s >= kNow - kWindowS - kSkewS && s.sent_s <= kNow + kSkewS;
    if (touched ? seal.ok : seal.ok != fresh) __builtin_trap();
    if (!seal.ok && seal.why.empty()) __builtin_trap();
    // The same seal from another node does not pass.
    if (check_receipt_seal(rest, kCustodyReceiptBytes, &auth, kSender + 1, kNow, kWindowS).ok) __builtin_trap();
    rest.remove_prefix(seal.used);
  }
  if (!rest.empty()) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::shared_ptr<MessageAuthenticator> auth = make_auth();
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (uint32_t id : {kDefaultEnvelopeId, 200u}) {
    walk_frame(bytes, id, nullptr);
    walk_frame(bytes, id, auth.get());
    check_payload(bytes, id, nullptr);
    check_payload(bytes, id, auth.get());
    check_sealed(bytes, id, *auth);
  }
  return 0;
}
