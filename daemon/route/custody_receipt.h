#pragma once
// Custody receipts: how a gateway says "I hold it" to the previous hop when
// its modem, not the daemon, acknowledges (README "Gateways: custody on a
// link whose modem ACKs").
//
// The problem. On a software-ACK link (sim, udp, Micro-Modem FDP) a gateway
// refuses custody by withholding its ACK, and ACKs only once the message is
// journaled. A Micro-Modem without FDP, or an Iridium 9603 whose session
// takes any queued MT with the MO, ACKs in the modem before the daemon sees
// the frame: the previous hop would forget the message at that ACK, so a
// full gateway could only take it over its bound or lose it.
//
// The decision. On such a link the modem's ACK of a wrapped message for a
// node beyond the next hop no longer ends it at the sender: it stays queued
// (and journaled), held, until the next hop sends a custody receipt about
// it, in software, heard back on the same link:
//   - "taken": sent only once the message is journaled in custody there
//     (or was already held, or its fate was decided there: its hop limit
//     or ttl ran out). The sender forgets it then.
//   - "refused": custody is full (routing.max_custody) or the store
//     failed; nothing was stored. The sender offers it again after a
//     back-off.
//   - nothing (the receipt was lost): the sender offers it again after its
//     wait; the next hop recognises the copy it holds and answers "taken"
//     again without storing it twice.
// A receipt is not a message: it is not queued, journaled, acknowledged,
// nor itself answered by a receipt (no receipt loops). It rides in the next
// frame this node sends on that link, after the messages (room kept for it
// before the contest), and may make a satellite modem open a session.
//
// Layout (7 bytes = 56 bits per receipt; several go back to back):
//   bytes 0-1  DCCL id header of the envelope id (as an envelope's)
//   byte  2    kind: 3 taken, 4 refused (an envelope's byte 2 has its hop
//              limit, 1-15, in the high nibble: never 3 or 4)
//   bytes 3-4  the message's origin, little-endian
//   bytes 5-6  the message's sequence, little-endian
//
// Thread-safe: pure functions and plain values.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "route/envelope.h"

namespace acomms::route {

enum class CustodyVerdict : uint8_t { kTaken = 3, kRefused = 4 };

inline constexpr size_t kCustodyReceiptBytes = 7;

struct CustodyReceipt {
  CustodyVerdict verdict = CustodyVerdict::kTaken;
  MessageIdentity about;
  bool operator==(const CustodyReceipt&) const = default;
};

std::string encode_custody_receipt(const CustodyReceipt& receipt, uint32_t envelope_id);

// Whether `bytes` begins like a custody receipt (the envelope id's header,
// then a verdict byte), whatever follows.
bool starts_custody_receipt(std::string_view bytes, uint32_t envelope_id);

// The custody receipt at the start of `bytes` (outside input), or nullopt
// when it is not one whole receipt.
std::optional<CustodyReceipt> decode_custody_receipt(std::string_view bytes, uint32_t envelope_id);

// "taken", "refused".
const char* to_string(CustodyVerdict verdict);

}  // namespace acomms::route
