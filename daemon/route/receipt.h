#pragma once
// Receipts: what a routed message's origin hears back about it from afar
// (README "Gateways: end-to-end acks and expiry reports").
//
// The problem. A hop ACK says the next node holds the message; the origin
// (a shore two hops from a vehicle) wants to know that the vehicle got it,
// or that it ran out of time on the way, and where. The answer must be
// cheap on links of tens of bytes a minute, and must cross the same
// gateways, which know nothing of it.
//
// The decision. A receipt is a routed message like any other: an envelope
// (route/envelope.h) from the node that reports (the destination, or the
// gateway where the message expired) to the message's origin, forwarded
// with custody, hop by hop, on the route back (static or learned). Only its
// payload is special: it starts with the envelope id's own DCCL id header,
// which no user type can have (the id is reserved), so it is never taken
// for a message and costs no second reserved id. Payload (5 bytes):
//
//   bytes 0-1  DCCL id header of the envelope id
//   byte  2    kind: 1 delivered (end-to-end ack), 2 expired
//   bytes 3-4  the message's sequence (its origin: the receipt's destination;
//              where: the receipt's origin), little-endian
//
// On the air: 13 + 5 = 18 bytes = 144 bits per hop, whatever the message's
// size. A nested envelope (another envelope inside the payload) has a
// byte 2 of 16 or more (its hop limit is in the high nibble), never 1 or 2,
// and stays refused.
//
// Thread-safe: pure functions and plain values.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace acomms::route {

enum class ReceiptKind : uint8_t { kDelivered = 1, kExpired = 2 };

inline constexpr size_t kReceiptBytes = 5;

struct Receipt {
  ReceiptKind kind = ReceiptKind::kDelivered;
  uint16_t seq = 0;  // of the message it is about
  bool operator==(const Receipt&) const = default;
};

// The payload of a receipt (envelope_id: 128..32767, as the envelope's).
std::string encode_receipt(const Receipt& receipt, uint32_t envelope_id);

// The receipt `payload` holds, or nullopt when it is not exactly one (a
// user's DCCL message, a nested envelope, a wrong length or kind).
std::optional<Receipt> decode_receipt(std::string_view payload, uint32_t envelope_id);

// "delivered", "expired".
const char* to_string(ReceiptKind kind);

}  // namespace acomms::route
