#pragma once
// Driver-specific transmissions: what one modem can do that the generic
// interface does not name (the Micro-Modem's ranging ping, LBL navigation,
// 13-bit mini-packets, MM2 FDP packets). Schneider (2013) §2.5 keeps such
// features out of the generic interface but within reach of an application
// that knows its hardware.
//
// The decision: one generic path. A request is a ModemTransmission of type
// DRIVER_SPECIFIC carrying the driver's own proto2 extension
// (api/proto/acomms/drivers/<driver>_transmission.proto); nothing above the
// driver reads the extension. The driver checks the request at once (before
// any wait for a slot: a request it cannot do fails now), then sends it when
// the LinkController says the channel is this node's, and answers `done`
// exactly once with the request's results filled in, or a status naming what
// went wrong. A driver that knows no such request answers kUnimplemented
// naming it (the default).
//
// Received driver-specific transmissions (a mini-packet from another modem)
// reach on_receive as type DRIVER_SPECIFIC with the driver's extension set;
// the LinkController hands each set extension message to subscribers as a
// message of its own type.
//
// Core thread only.

#include <functional>
#include <string>

#include "acomms/v1/modem_transmission.pb.h"

namespace acomms::link {

// The outcome's kind; each maps to one gRPC status code in the service.
enum class DriverSpecificStatus {
  kOk,
  kInvalidArgument,     // a field out of its bound (named)
  kFailedPrecondition,  // the modem cannot do it (e.g. FDP on an MM1)
  kUnimplemented,       // the driver does not support the request (named)
  kDeadlineExceeded,    // no slot in time, or no answer in time
  kUnavailable,         // the driver is down
  kAborted,             // the exchange failed on the way (reboot, refusal)
};

struct DriverSpecificResult {
  DriverSpecificStatus status = DriverSpecificStatus::kOk;
  std::string error;                 // "" when kOk
  v1::ModemTransmission transmission;  // the request, results filled in
  double waited_s = 0;               // waiting for the channel (the gate's)
};

using DriverSpecificDone = std::function<void(DriverSpecificResult)>;

// Names what a request asks for, for errors: its set extensions' full
// names ("acomms.drivers.micromodem_transmission"), the numbers of extensions this
// binary does not know ("extension 1100"), or "no extension".
std::string describe_driver_specific(const v1::ModemTransmission& request);

DriverSpecificResult driver_specific_error(DriverSpecificStatus status, std::string error,
                                           const v1::ModemTransmission& request);

}  // namespace acomms::link
