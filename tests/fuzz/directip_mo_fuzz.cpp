// libFuzzer target: DirectIP MO messages, which anyone who can reach the
// shore's MO port can send. parse_mo() must refuse what it cannot use, with
// a reason; what it accepts must respect the spec's bounds (a 15-digit
// IMEI, a payload of at most 340 bytes), and the MT confirmation parser,
// fed the same bytes, must behave the same way.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "iridium_shore/direct_ip.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace acomms::drivers::directip;
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::string error;
  std::optional<MoMessage> mo = parse_mo(bytes, &error);
  if (!mo) {
    if (error.empty()) __builtin_trap();  // every refusal must say why
  } else {
    if (mo->header.imei.size() != kImeiDigits || mo->payload.size() > kMaxMoPayload) __builtin_trap();
    if (size != kPrefixBytes + ((static_cast<size_t>(data[1]) << 8) | data[2])) __builtin_trap();
    if (mo->location && (mo->location->latitude_deg < -91 || mo->location->latitude_deg > 91)) __builtin_trap();
  }
  error.clear();
  if (!parse_mt_confirmation(bytes, &error) && error.empty()) __builtin_trap();
  return 0;
}
