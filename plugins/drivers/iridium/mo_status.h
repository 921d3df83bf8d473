#pragma once
// The MO status of +SBDIX (spec §5.1's table) as what the driver does next.
//
// One table, one place: the session code asks classify_mo_status() and
// never tests codes itself, so the spec's table and the driver cannot drift
// apart. Reserved codes follow the spec (3, 4 success; the rest failure,
// retried with back-off). `maybe_at_gateway` is the spec's inferred "dup?"
// column: a retry after such a failure may duplicate the MO on shore, which
// the shore's dedup (IMEI, MOMSN, payload) and the receiver's duplicate
// window remove.
//
// Thread-safe: pure functions.

#include <chrono>

namespace acomms::drivers::iridium {

enum class MoAction {
  kSuccess,       // 0..4: the MO (if any) is at the gateway
  kRetry,         // back-off schedule (spec §6.3)
  kRetryLater,    // a long fixed wait (11, 35, 36, 37, 38: `wait`)
  kDropFrame,     // 12, 14: this frame can never go; give it back to the queues
  kFault,         // 15, 16, 64, 65: raise a fault, retry every 30 min
  kWaitService,   // 32: no network: wait for service, then retry
  kAntennaFault,  // 33: fault, retry slowly (5 min)
  kRadioOff,      // 34: AT*R1, then retry
};

struct MoOutcome {
  MoAction action = MoAction::kRetry;
  const char* meaning = "";
  bool maybe_at_gateway = false;
  std::chrono::seconds wait{0};  // the least wait before the next session
};

MoOutcome classify_mo_status(int code);

const char* to_string(MoAction action);

}  // namespace acomms::drivers::iridium
