#pragma once
// Little-endian fixed-width integers: the byte order of the state a stream
// end keeps in the store (telemetry/state_bytes.h, telemetry/stream_history)
// and of the sim driver's envelope on the wire.
//
// Each of those wrote its own shift loop; one slip in one copy (a wrong
// shift, a sign-extended char) would change bytes that are stored or sent,
// so the loop is written once, here. Widths are 1 to 8 bytes; a value wider
// than its width is cut to its low bytes, as the loops always did.
//
// Thread-safe: pure functions.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace acomms::util {

// Appends the low `bytes` bytes of `value`, least significant first.
inline void put_le(std::string* out, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out->push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

// The `bytes`-byte value at p, least significant first. The caller has
// checked that `bytes` bytes are there.
inline uint64_t load_le(const unsigned char* p, int bytes) {
  uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) value |= uint64_t{p[i]} << (8 * i);
  return value;
}

// Takes a `bytes`-byte value from the front of *in. Returns false, leaving
// *in as it was, when fewer bytes remain: stored bytes may be short (another
// version, a torn write), and that is the caller's decision, not a crash.
inline bool take_le(std::string_view* in, int bytes, uint64_t* value) {
  if (in->size() < static_cast<size_t>(bytes)) return false;
  *value = load_le(reinterpret_cast<const unsigned char*>(in->data()), bytes);
  in->remove_prefix(static_cast<size_t>(bytes));
  return true;
}

}  // namespace acomms::util
