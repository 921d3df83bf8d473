#pragma once
// The routing envelope: how a message for a node that is not a neighbour
// travels through gateways that never decode its type.
//
// The problem. A frame is DCCL messages back to back with no lengths
// (queue/frame_building.cpp): a receiver finds where one message ends only
// by decoding it, so it must have loaded its type. A message's destination
// is a field of the user's type (the queue's destination role), and a link
// ACK covers a transmission between neighbours, not the message's journey.
// A gateway buoy that forwards a vehicle's command from shore would have to
// load every type of every vehicle, know each type's roles, and could not
// tell two copies of one message from two messages.
//
// The decision. A routed message travels wrapped: an envelope that starts
// like a DCCL message (a DCCL id header, so a frame may mix envelopes and
// plain messages, and an old receiver counts it as an unknown id and stops
// there, as with any type it lacks), then a fixed head that says what a
// gateway needs, then the length of the message's DCCL bytes and the bytes
// themselves, opaque. Layout (byte-aligned, integers little-endian):
//
//   bytes 0-1   DCCL id header of the envelope id (routing.envelope_id,
//               default 32767; ids >= 128 take two bytes: ((id<<1)|1) LE)
//   byte  2     bits 0-3 hops taken so far (0-15), bits 4-7 hop limit (1-15)
//   bytes 3-4   origin: the modem id of the node that submitted the message
//   bytes 5-6   final destination (modem id, never 0: no routed broadcast)
//   bytes 7-8   sequence, per origin (the origin's journal id mod 2^16)
//   bytes 9-10  remaining ttl, whole seconds (0-65535)
//   byte  11    priority: the type's value_base in tenths (0-255 -> 0-25.5)
//   byte  12    length of the message's DCCL bytes (1-255)
//   bytes 13-   the message's DCCL bytes, as its origin encoded them
//
// Cost: 13 bytes = 104 bits per routed message on every hop. Plain traffic
// (a node without `routing`, or a message whose destination is a neighbour)
// carries no envelope and is byte-identical to DCCL 4.
//
// The message's identity is (origin, sequence): every copy on every path
// carries the same one, so a destination delivers a message once however
// many ways it arrived, and a gateway recognises a copy it already holds.
// The sequence wraps at 2^16: an origin submitting more than 65536 routed
// messages within the destination's duplicate window would alias.
//
// Invariant: decode_envelope(encode_envelope(e)) == e for every e that
// encodes; decode never reads past its input and says why it refuses.
//
// Thread-safe: pure functions and plain values.

#include <compare>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace acomms::route {

inline constexpr uint32_t kDefaultEnvelopeId = 32767;
inline constexpr uint32_t kMaxHopLimit = 15;
inline constexpr uint32_t kDefaultHopLimit = 8;
// The envelope's bytes before the message's own (id header included).
inline constexpr size_t kEnvelopeOverheadBytes = 13;
inline constexpr size_t kMaxPayloadBytes = 255;
inline constexpr uint32_t kMaxTtlSeconds = 65535;

// Which message this is, whatever path a copy took.
struct MessageIdentity {
  uint16_t origin = 0;
  uint16_t seq = 0;
  auto operator<=>(const MessageIdentity&) const = default;
};

struct Envelope {
  uint16_t origin = 0;
  uint16_t destination = 0;
  uint16_t seq = 0;
  uint8_t hops = 0;
  uint8_t hop_limit = kDefaultHopLimit;
  uint16_t ttl_s = 0;         // remaining when this copy was sent
  uint8_t value_tenths = 10;  // value_base x 10
  std::string payload;        // the message's DCCL bytes (opaque here)

  MessageIdentity identity() const { return {origin, seq}; }
  bool operator==(const Envelope&) const = default;
};

// The envelope's bytes. Throws std::invalid_argument naming the field when
// a value does not fit its place (empty or > 255-byte payload, destination
// 0, hops > limit, limit 0 or > 15) or envelope_id is not 128..32767.
std::string encode_envelope(const Envelope& envelope, uint32_t envelope_id);

// Whether `bytes` begins with the DCCL id header of `envelope_id`: the
// receive side's one test before it decodes any type.
bool starts_envelope(std::string_view bytes, uint32_t envelope_id);

// The envelope at the start of `bytes` (outside input: a received frame).
// On success *used is its length (a frame may hold more after it). On
// refusal returns nullopt and *error says why (not an envelope, truncated,
// a field out of range); nothing is assumed about the bytes after.
std::optional<Envelope> decode_envelope(std::string_view bytes, uint32_t envelope_id, size_t* used,
                                        std::string* error);

// value_base (>= 0) in the envelope's tenths, saturating at 255.
uint8_t value_to_tenths(double value_base);
// Remaining ttl in whole seconds (rounded down, saturating at 65535; a
// negative or NaN ttl is 0).
uint16_t ttl_to_seconds(double ttl_s);

}  // namespace acomms::route
