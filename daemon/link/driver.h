#pragma once
// The one interface for any slow link: an acoustic modem over serial, a UDP
// link, a satellite modem, the simulator.
//
// A driver lives on the core thread. The MAC calls initiate_transmission()
// at the start of a slot; for a DATA transmission from this node the driver
// fills in max_num_frames / max_frame_bytes for the rate and asks for data
// (on_data_request, answered synchronously by the queues), sends it, and
// reports the result. What arrives is reported with on_receive: DATA, and
// ACKs for our own DATA (acked_frame lists the frame indices). Drivers for
// modems that acknowledge by themselves (the Micro-Modem does) send ACKs for
// DATA addressed to this node with ack_requested; others must do the same
// in software so that every link behaves alike.
//
// A transmission whose src is not this node's id is a poll: the driver asks
// node src to send its data now (Micro-Modem "third-party" cycle
// initialization). The polled node's driver, on hearing it, makes a data
// request and transmits as if its own MAC had asked.

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "acomms/v1/modem_transmission.pb.h"

namespace acomms::link {

struct DriverCallbacks {
  // A transmission arrived (DATA for anyone — filter by dest — or ACK).
  std::function<void(const v1::ModemTransmission&)> on_receive;
  // Fill `transmission` (frames, and dest when it is -1) for sending now.
  std::function<void(v1::ModemTransmission* transmission)> on_data_request;
  // A transmission we started went out (ok) or could not (error says why).
  std::function<void(const v1::ModemTransmission&, bool ok, const std::string& error)> on_transmit_result;
  // Raw bytes to and from the device, for logs and debugging.
  std::function<void(std::string_view bytes, bool outgoing)> on_raw;
};

// A failure of the driver or its device (port gone, peer unreachable). The
// DriverSupervisor reports it and restarts the driver after a backoff.
class DriverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Driver {
 public:
  virtual ~Driver() = default;
  // Opens the device and begins reporting through `callbacks`. Throws
  // DriverError when the device cannot be opened.
  virtual void start(DriverCallbacks callbacks) = 0;
  // Closes the device; no callback runs after it returns. Idempotent.
  virtual void stop() = 0;
  // Called periodically (a few times a second) on the core thread: polls
  // the device, handles timeouts. Throws DriverError on a device failure.
  virtual void do_work() = 0;
  // Starts a transmission (see the file comment). Throws DriverError.
  virtual void initiate_transmission(const v1::ModemTransmission& transmission) = 0;
};

}  // namespace acomms::link
