#include "iridium/mo_status.h"

namespace acomms::drivers::iridium {

using std::chrono::seconds;

MoOutcome classify_mo_status(int code) {
  switch (code) {
    case 0: return {MoAction::kSuccess, "MO transferred", false, {}};
    case 1: return {MoAction::kSuccess, "MO transferred; the queued MT is too big for this modem", false, {}};
    case 2: return {MoAction::kSuccess, "MO transferred; location update refused", false, {}};
    case 3:
    case 4: return {MoAction::kSuccess, "reserved (success)", false, {}};
    case 10: return {MoAction::kRetry, "gateway: call did not complete in time", true, {}};
    case 11: return {MoAction::kRetryLater, "gateway: MO queue for this modem full", false, seconds(300)};
    case 12: return {MoAction::kDropFrame, "MO has too many segments", false, {}};
    case 13: return {MoAction::kRetry, "gateway: session did not complete", true, {}};
    case 14: return {MoAction::kDropFrame, "invalid segment size", false, {}};
    case 15: return {MoAction::kFault, "access denied (not provisioned, no line rental)", false, seconds(1800)};
    case 16: return {MoAction::kFault, "modem locked", false, seconds(1800)};
    case 17: return {MoAction::kRetry, "gateway not responding", true, {}};
    case 18: return {MoAction::kRetry, "connection lost (RF drop)", true, {}};
    case 19: return {MoAction::kRetry, "link failure", true, {}};
    case 32: return {MoAction::kWaitService, "no network service", false, {}};
    case 33: return {MoAction::kAntennaFault, "antenna fault", false, seconds(300)};
    case 34: return {MoAction::kRadioOff, "radio disabled", false, {}};
    case 35: return {MoAction::kRetryLater, "modem busy", false, seconds(10)};
    case 36: return {MoAction::kRetryLater, "must wait 3 min since the last registration", false, seconds(180)};
    case 37: return {MoAction::kRetryLater, "SBD service temporarily disabled", false, seconds(300)};
    case 38: return {MoAction::kRetryLater, "try later: traffic management period", false, seconds(300)};
    case 64: return {MoAction::kFault, "band violation", false, seconds(1800)};
    case 65: return {MoAction::kFault, "PLL lock failure (hardware)", false, seconds(1800)};
    default: return {MoAction::kRetry, "reserved (failure)", true, {}};
  }
}

const char* to_string(MoAction action) {
  switch (action) {
    case MoAction::kSuccess: return "success";
    case MoAction::kRetry: return "retry with back-off";
    case MoAction::kRetryLater: return "retry after a wait";
    case MoAction::kDropFrame: return "frame dropped";
    case MoAction::kFault: return "fault";
    case MoAction::kWaitService: return "waiting for service";
    case MoAction::kAntennaFault: return "antenna fault";
    case MoAction::kRadioOff: return "radio off";
  }
  return "?";
}

}  // namespace acomms::drivers::iridium
