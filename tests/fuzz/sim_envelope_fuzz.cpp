// libFuzzer target: sim envelopes from the loopback UDP port, which anything
// on the machine can write to. decode_envelope() must reject what it cannot
// use; what it accepts must re-encode to the same bytes and must be safe for
// hearing(), whose time arithmetic UBSan checks here for overflow.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "sim/sim_envelope.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace acomms::drivers;
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::string error;
  std::optional<SimEnvelope> envelope = decode_envelope(bytes, &error);
  if (!envelope) {
    if (error.empty()) __builtin_trap();  // every refusal must say why
    return 0;
  }
  // Protobuf may parse the transmission from bytes it would not write
  // itself, so compare a second round trip, not the input.
  std::string once = encode(*envelope);
  std::optional<SimEnvelope> again = decode_envelope(once, &error);
  if (!again || encode(*again) != once) __builtin_trap();
  // Receivers anywhere in range, at the slowest and the usual sound speed.
  for (const SimPosition& at : {SimPosition{0, 0, 0}, SimPosition{-1e7, 1e7, -1e7}}) {
    for (double sound_speed : {1.0, 1500.0}) {
      if (auto heard = hearing(*envelope, at, sound_speed); heard && heard->end < heard->start) __builtin_trap();
    }
  }
  return 0;
}
