#pragma once
// Sealed receipts: end-to-end receipts (route/receipt.h) and custody
// receipts (route/custody_receipt.h) under the fleet's authentication key
// (README "Authenticated types", dccl/message_auth.h).
//
// The problem. A receipt tells a node to forget a message ("taken") or
// that it arrived ("delivered"). Anyone with a compatible modem could send
// one: a forged "delivered" makes an origin believe a command reached its
// vehicle, a forged "taken" makes the previous hop drop a message nobody
// holds.
//
// The decision. When the node has an authenticator (its config's auth
// section lists a type), every receipt it sends carries the DCCL trailer
// after its bytes (key id, send time, counter, tag: 48 + tag_bits bits,
// 80 to 112), sealed as this node; every receipt it hears must carry one
// that verifies as from the node that reports (an end-to-end receipt's
// envelope origin, a custody receipt's transmission source), stamped
// within the window (the custody ttl, plus 60 s of clock skew either way);
// an unsealed or forged one is refused (counted, logged) and changes
// nothing. A replay inside the window is harmless: a receipt is about one
// noted message, and its note is taken by the first. Without an
// authenticator nothing is sealed or checked (byte-identical to before).
// A fleet turns auth on at every node at once: a node with auth refuses
// the receipts of one without.
//
// Thread-safe: pure functions (the authenticator is thread-safe).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "dccl/message_auth.h"

namespace acomms::route {

// Appends the trailer to `bytes` when `auth` is set.
void seal_receipt(std::string& bytes, const dccl::MessageAuthenticator* auth, double now);

// The receipt's bytes on the air: `receipt_bytes`, plus the trailer with auth.
size_t sealed_size(size_t receipt_bytes, const dccl::MessageAuthenticator* auth);

struct SealCheck {
  bool ok = true;
  size_t used = 0;  // bytes of `rest` the sealed receipt takes (as many as there are when refused)
  std::string why;  // when refused: "no seal", "bad tag", "stale", ...
};

// Whether the receipt of `receipt_bytes` at the start of `rest` is sealed
// by `sender` within `window_s` of `now`; always ok without `auth`.
SealCheck check_receipt_seal(std::string_view rest, size_t receipt_bytes, const dccl::MessageAuthenticator* auth,
                             int32_t sender, double now, double window_s);

}  // namespace acomms::route
