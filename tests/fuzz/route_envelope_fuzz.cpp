// libFuzzer target: routing envelopes (route/envelope.h) from received
// frames, which any node in range (or a broken one) can put on the water.
// decode_envelope() must refuse what it cannot use, saying why, and never
// read past its input; what it accepts must say how many bytes it used
// (no more than it was given) and encode back to exactly those bytes. An
// envelope's payload may be a receipt (route/receipt.h, an end-to-end ack or
// an expiry report): decode_receipt() takes exactly one or nothing.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "route/envelope.h"
#include "route/receipt.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace acomms::route;
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The default id, and one whose header the first bytes may well be.
  for (uint32_t id : {kDefaultEnvelopeId, 200u}) {
    size_t used = 0;
    std::string error;
    std::optional<Envelope> envelope = decode_envelope(bytes, id, &used, &error);
    if (!envelope) {
      if (error.empty()) __builtin_trap();  // every refusal must say why
      continue;
    }
    if (used > bytes.size() || used != kEnvelopeOverheadBytes + envelope->payload.size()) __builtin_trap();
    if (!starts_envelope(bytes, id)) __builtin_trap();
    if (encode_envelope(*envelope, id) != bytes.substr(0, used)) __builtin_trap();
  }
  for (uint32_t id : {kDefaultEnvelopeId, 200u}) {
    std::optional<Receipt> receipt = decode_receipt(bytes, id);
    if (receipt && (bytes.size() != kReceiptBytes || encode_receipt(*receipt, id) != bytes)) __builtin_trap();
  }
  return 0;
}
