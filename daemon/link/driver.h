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
//
// Timing: a packet must not outrun its slot (link/slot_budget.h), so the
// link asks the driver how long its packets are in the water. The defaults
// are a real modem's estimate: the Micro-Modem rate table's figures
// (link/rate_table.h) plus kAirTimeMargin. A driver that knows better (the
// simulator knows its own figures exactly; a link without air time, UDP,
// has none) overrides them.
//
// Losses only the driver sees (a packet heard while transmitting, two that
// overlapped) are counted in DriverCounters, for LinkStatus.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "acomms/v1/modem_transmission.pb.h"
#include "link/driver_specific.h"

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
  // Runs `then` on the core thread once everything on_receive has passed on
  // so far is durable (its received events committed to the store), or
  // never if that commit fails. A software ACK waits for it: an ACK tells
  // the sender to forget the message, so it must not go out while a crash
  // could still lose the only copy. Unset: at once (no store).
  std::function<void(std::function<void()> then)> after_receipt_durable;
  // A packet was heard but did not decode (the simulator's failed draw):
  // src, dest, type, the rate whose reception curve applied, time, and the
  // figures the driver has (the model's prediction); never frames. For the
  // record only (a "packet" event, acommsctl link calibrate). Unset: dropped.
  std::function<void(const v1::ModemTransmission&)> on_reception_failed;
};

// A failure of the driver or its device (port gone, peer unreachable). The
// DriverSupervisor reports it and restarts the driver after a backoff.
class DriverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a real modem's estimate adds to the rate table's air time: the
// figures are derived, not measured (rate_table.h), so a slot keeps room.
inline constexpr double kAirTimeMargin = 0.10;

// Packets the driver knows it lost, since it was built. All zero for a
// driver that cannot tell.
struct DriverCounters {
  uint64_t lost_half_duplex = 0;  // arrived while this node transmitted
  uint64_t lost_collision = 0;    // overlapped another packet arriving
  // Input from the modem the driver could not use, by kind (Micro-Modem:
  // "noise" in bytes, "bad checksum", "truncated line", ... in lines);
  // the driver logs it once per burst, these say how much there was.
  std::map<std::string, uint64_t> bad_input{};

  DriverCounters& operator+=(const DriverCounters& other);
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

  // How long a DATA packet of `num_frames` frames at `rate` is in the water
  // (zero for a rate outside the table). Default: rate table + margin.
  virtual std::chrono::nanoseconds packet_air_time(int32_t rate, uint32_t num_frames) const;
  // From the end of a DATA packet heard to the end of its ACK in the water:
  // the receiver's turnaround plus the ACK's air time. Default: 0.5 s plus
  // a mini-packet (rate_table.h), plus the margin.
  virtual std::chrono::nanoseconds ack_time(int32_t rate) const;
  // How fast packets travel, m/s, for the guard that covers the longest
  // range (mac.max_range_m); 0: they arrive at once (no guard). Default:
  // kNominalSoundSpeed.
  virtual double sound_speed() const;
  // Losses this driver has seen (see DriverCounters).
  virtual DriverCounters counters() const { return {}; }

  // Driver-specific transmissions (link/driver_specific.h). check: before
  // any wait, whether the request can be done (status kOk) or why not.
  // Default: kUnimplemented naming the request.
  virtual DriverSpecificResult check_driver_specific(const v1::ModemTransmission& request) const;
  // Sends a checked request now (the channel is this node's); `done` runs
  // exactly once, at the latest shortly after `deadline_s` (seconds since
  // the Unix epoch, the driver's clock). Default: kUnimplemented.
  virtual void send_driver_specific(const v1::ModemTransmission& request, double deadline_s,
                                    DriverSpecificDone done);
  // The modem as it identified itself (Micro-Modem: "MM2 2.0.27087" from
  // its $CAREV), for LinkStatus; "" when the driver does not know.
  virtual std::string modem() const { return ""; }
  // Whether the device itself acknowledges a DATA transmission that asks for
  // it (a Micro-Modem's $CAACK, an Iridium gateway's receipt) before the
  // daemon sees it: an ACK then cannot wait for what the daemon does with
  // the frames (a gateway's custody, route/forwarder.h). Default: false,
  // the DriverSequence's software ACK, sent once receipts are durable.
  virtual bool acks_in_hardware() const { return false; }
};

}  // namespace acomms::link
