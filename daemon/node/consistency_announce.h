#pragma once
// The consistency announce on the water: how a node tells its neighbours
// the digest of what must agree across the fleet (node/consistency_digest.h)
// in a few bytes of a frame's spare space (queue/piggyback.h).
//
// The problem. A frame is DCCL messages back to back without lengths; a
// receiver finds where one ends only by decoding it. An announce must be
// readable by nodes that know it and harmless to nodes that do not (an
// older acommsd, or one with consistency disabled): such a node meets an
// unknown DCCL id and drops the rest of the frame.
//
// The decision. The announce starts like a DCCL message of a reserved id
// (consistency.announce_id, default 32766, next to the routing envelope's
// 32767; refused at start if a loaded type uses it), so it is told apart
// before any type is looked up; it is always the last thing in its frame,
// so the bytes an unknowing receiver drops are only its own. Layout:
//
//   bytes 0-1   DCCL id header of the announce id ((id<<1)|1, LE: ids >= 128
//               take two bytes)
//   bytes 2-5   the digest, most significant byte first (the order of its
//               hex form: the first 4 bytes of the SHA-256)
//
// Cost: kAnnounceBytes = 6 bytes = 48 bits, on each link at start and then
// every consistency.announce_interval_s (default 600 s), only where no
// queued message could have gone (and, on a slotless link, only with
// queued messages: queue/piggyback.h).
//
// Invariant: decode_announce(encode_announce(d, id), id) == d; decode never
// reads past its input and says why it refuses.
//
// Thread-safe: pure functions.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace acomms::node {

inline constexpr uint32_t kDefaultAnnounceId = 32766;
inline constexpr size_t kAnnounceBytes = 6;

// Throws std::invalid_argument unless 128 <= announce_id <= 32767.
std::string encode_announce(uint32_t digest, uint32_t announce_id);

// Whether `bytes` begins with the DCCL id header of `announce_id`.
bool starts_announce(std::string_view bytes, uint32_t announce_id);

// The digest of the announce at the start of `bytes` (outside input: a
// received frame); what follows its kAnnounceBytes is not looked at. On
// refusal nullopt, and *error (if given) says why.
std::optional<uint32_t> decode_announce(std::string_view bytes, uint32_t announce_id, std::string* error);

}  // namespace acomms::node
