#pragma once
// The state of a transport (serial port, TCP connection, UDP socket), as it
// reports it to its owner and, through it, to the LinkStatus API.
//
// Values and a callback type: each transport calls its TransportStateCallback
// on the core thread (serial_transport.h, tcp_client_transport.h,
// udp_transport.h).

#include <functional>
#include <string>

namespace acomms::link {

enum class TransportState {
  kClosed,   // not opened, or closed by its owner
  kOpening,  // an attempt to open or connect is under way
  kOpen,     // bytes flow
  kWaiting,  // the device or peer went away; a retry is scheduled
};

const char* to_string(TransportState state);

// Called on every change; `detail` names the device or address and, when
// the transport is waiting, the error and when it retries.
using TransportStateCallback = std::function<void(TransportState state, const std::string& detail)>;

// How a transport retries (seconds; see Backoff).
struct RetryOptions {
  double min_s = 1;
  double max_s = 60;
};

}  // namespace acomms::link
