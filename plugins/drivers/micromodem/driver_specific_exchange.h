#pragma once
// The Micro-Modem's own transmissions (link/driver_specific.h; requests in
// api/proto/acomms/drivers/micromodem_transmission.proto): two-way ping,
// narrowband and REMUS LBL, 13-bit user mini-packets and MM2 FDP packets
// (spec §6-§7, sequences §8.4-§8.5, timeouts §7.1 and §9).
//
// One at a time, like the modem itself. The LinkController decides when
// (this node's slot, or a poll's channel); this class checks a request at
// once (driver_specific_request.h: bounds, MM2-only features, FDP
// configured), sends its command
// through the CommandQueue (echo-confirmed, never repeated: a repeated ping
// would be a second ping) and waits for the answer:
//   ping        $CCMPC → $CAMPC … $CAMPR from dest: one-way travel time;
//               none within 2 × max range / c + 3 s (§7.1): timed out
//   LBL         [$CCCFG,TAT] → $CCPNT/$CCPDT → $SNPNT/$SNPDT … $SNTTA
//               (within Timeout + 2 s)
//   mini-packet $CCMUC → $CAMUC … $CATXF (no reply is waited for, §7.4)
//   FDP         $CCTDP → $CATDP … $CATXF … the destination's software ACK
// FDP firmware ACKs are not to be relied on (§6), so FDP data carries a
// two-byte header (0xFD, sequence) and the destination's driver answers at
// once with its own FDP packet (0xFA, sequence), as the other drivers ACK
// in software; like the modem's own ACKs it goes out in the sender's slot.
// Received mini-packets and FDP data are reported as DRIVER_SPECIFIC
// transmissions carrying MicroModemMiniPacket / MicroModemFdpPacket.
//
// Every wait is also bounded by the caller's deadline. Core thread only.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "acomms/drivers/micromodem_transmission.pb.h"
#include "core/scheduler.h"
#include "link/driver_specific.h"
#include "micromodem/command_queue.h"
#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/fdp_sentences.h"
#include "micromodem/nmea/mini_packet_sentences.h"
#include "micromodem/nmea/ranging_sentences.h"

namespace acomms::drivers::micromodem {

class DriverSpecificExchange {
 public:
  struct Settings {
    int32_t own_id = 1;
    double time_scale = 1;      // the driver's waits are divided by it
    double sound_speed = 1500;  // m/s, for ranges
    double max_range_m = 2000;  // for the ping's timeout
    bool fdp_configured = false;  // cfg sets psk.packet.mod_hdr_version 1
    std::vector<int32_t> mm1_modems;  // other nodes known to be MM1 (no FDP to them)
  };
  struct Hooks {
    // The modem's generation, when known (FDP needs an MM2).
    std::function<std::optional<::acomms::micromodem::ModemGeneration>()> generation;
    // A received mini-packet or FDP packet, for on_receive.
    std::function<void(const v1::ModemTransmission&)> received;
    std::function<double()> now_s;
  };
  struct Counters {
    uint64_t sent = 0;
    uint64_t failed = 0;
    uint64_t mini_packets_received = 0;
    uint64_t fdp_received = 0;
    uint64_t fdp_acks_sent = 0;
  };

  DriverSpecificExchange(core::Scheduler& scheduler, CommandQueue& commands, Settings settings, Hooks hooks);
  ~DriverSpecificExchange();

  link::DriverSpecificResult check(const v1::ModemTransmission& request) const;
  // REQUIRES: check(request) is kOk. `done` runs exactly once.
  void send(const v1::ModemTransmission& request, double deadline_s, link::DriverSpecificDone done);
  bool idle() const { return !current_; }

  // Sentences that may concern an extra; true when one was used here.
  bool on_ping_reply(const ::acomms::micromodem::PingReply& reply);
  bool on_travel_times(const ::acomms::micromodem::TravelTimes& times);
  bool on_transmit_finished();
  void on_mini_packet(const ::acomms::micromodem::MiniPacket& packet);
  void on_fdp_received(const ::acomms::micromodem::FdpReceived& packet);
  // Fails the extra in progress (reboot, stop).
  void abort(const std::string& why);

  const Counters& counters() const { return counters_; }

 private:
  enum class Phase { kCommand, kAwaitReply, kAwaitTransmitted, kAwaitAck };
  struct Current {
    v1::ModemTransmission request;
    drivers::MicroModemTransmission ask;
    link::DriverSpecificDone done;
    Phase phase = Phase::kCommand;
    double deadline_s = 0;
    uint8_t fdp_sequence = 0;
    uint64_t id = 0;
    core::Scheduler::TaskId timer = 0;
  };
  using Duration = std::chrono::system_clock::duration;

  void start_lbl();
  void send_command(const ::acomms::micromodem::Sentence& sentence,
                    std::function<bool(const ::acomms::micromodem::Sentence&)> is_reply, Phase next,
                    Duration wait);
  // Waits `modem_time` (divided by the time scale), at most to the deadline.
  void wait(Phase phase, Duration modem_time, std::string what);
  void finish(link::DriverSpecificStatus status, std::string error);
  void succeed();
  Duration scaled(Duration modem_time) const;
  void send_fdp_ack(int destination, int rate, uint8_t sequence);

  core::Scheduler& scheduler_;
  CommandQueue& commands_;
  Settings settings_;
  Hooks hooks_;
  std::optional<Current> current_;
  uint64_t next_id_ = 1;
  uint8_t next_fdp_sequence_ = 0;
  std::optional<int> turnaround_ms_;  // TAT as last written
  Counters counters_;
};

}  // namespace acomms::drivers::micromodem
