// libFuzzer target: consistency announces (node/consistency_announce.h) from
// received frames, which any node in range (or a broken one) can put on the
// water. decode_announce() must refuse what it cannot use, saying why, and
// never read past its input; what it accepts must start with the announce's
// header, be at least kAnnounceBytes long and encode back to exactly its
// first kAnnounceBytes bytes.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "node/consistency_announce.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace acomms::node;
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The default id, one whose header the first bytes may well be, and ids
  // out of range.
  for (uint32_t id : {kDefaultAnnounceId, 200u, 127u, 40000u}) {
    std::string error;
    std::optional<uint32_t> digest = decode_announce(bytes, id, &error);
    if (!digest) {
      if (error.empty()) __builtin_trap();  // every refusal must say why
      continue;
    }
    if (bytes.size() < kAnnounceBytes || !starts_announce(bytes, id)) __builtin_trap();
    if (encode_announce(*digest, id) != bytes.substr(0, kAnnounceBytes)) __builtin_trap();
  }
  return 0;
}
