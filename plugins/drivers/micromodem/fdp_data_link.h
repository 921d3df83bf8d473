#pragma once
// The queue's DATA as MM2 FDP packets (driver.micromodem.fdp_data; spec §6,
// sizes §3.2): one $CCTDP carries the frames the queues built, instead of
// the $CCCYC / $CADRQ / $CCTXD cycle, and a received $CARDP in this format
// becomes received DATA again.
//
// FDP firmware ACKs are not to be relied on (§6), so the DriverSequence runs
// with software_acks on when this is configured, as the sim and udp drivers
// do: its ACK goes out through here as an FDP packet too, and a received one
// becomes an ACK transmission for the queues.
//
// Payload formats (our own; FDP carries bytes only), distinct from the
// driver-specific FDP markers (0xFD, 0xFE, 0xFA) so both can share a network:
//   DATA 0xDD, ack_requested (0/1), then per frame: length (2 bytes, big
//        endian) and its bytes
//   ACK  0xDA, count, then one acked frame index per byte
// An odd total gets one zero byte at the end (MM2 builds before 2.0.35490
// mishandle odd lengths, §6); the readers ignore a trailing byte too short
// to be a frame.
//
// One packet at a time: after the echo ($CATDP) the packet is on the air
// until $CATXF. Core thread only.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "acomms/v1/modem_transmission.pb.h"
#include "core/scheduler.h"
#include "micromodem/command_queue.h"
#include "micromodem/nmea/fdp_sentences.h"

namespace acomms::drivers::micromodem {

class FdpDataLink {
 public:
  struct Hooks {
    // A transmission's result (only those sent with report).
    std::function<void(const v1::ModemTransmission&, bool ok, const std::string& error)> report;
    // Received DATA or ACK, for the DriverSequence.
    std::function<void(const v1::ModemTransmission&)> received;
    std::function<double()> now_s;
  };

  FdpDataLink(core::Scheduler& scheduler, CommandQueue& commands, int32_t own_id, double time_scale, Hooks hooks);
  ~FdpDataLink();

  // How many of the rate's frames fit one FDP packet at `rate` with this
  // format's header; 0 for a rate FDP does not have (only 1, 3, 5).
  static uint32_t max_num_frames(int32_t rate);

  // Our DATA (with frames) or a software ACK; "" when it goes out, else why not.
  std::string send(const v1::ModemTransmission& transmission, bool report);
  // $CATXF: true when it ended our packet.
  bool on_transmit_finished();
  // A $CARDP: true when it was in this format (and used here).
  bool on_received(const ::acomms::micromodem::FdpReceived& packet);
  void abort(const std::string& why);
  bool idle() const { return !current_; }

 private:
  struct Current {
    v1::ModemTransmission transmission;
    bool report = false;
    bool on_air = false;
    core::Scheduler::TaskId timer = 0;
  };
  void finish(bool ok, const std::string& error);

  core::Scheduler& scheduler_;
  CommandQueue& commands_;
  int32_t own_id_;
  double time_scale_;
  Hooks hooks_;
  std::optional<Current> current_;
  uint64_t generation_ = 0;  // tells a stale callback from the current packet's
};

}  // namespace acomms::drivers::micromodem
