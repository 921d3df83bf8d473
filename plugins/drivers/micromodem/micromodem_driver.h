#pragma once
// "micromodem": the WHOI Micro-Modem (MM1 and MM2) over its NMEA-0183
// interface (/work/shared/spec/micromodem-nmea.md; §11 maps it to
// link/driver.h).
//
// The problem: the modem is a state machine of its own on a serial line
// that may carry noise, reboots (`$CAREV` at any time), refusals and
// silence; the MAC and the queues must see it as any other driver: one
// result per transmission, received DATA, ACKs for our frames.
// The decision: this class reads and writes lines and routes each sentence
// to the one part that owns it, one concept per file:
//   micromodem_settings — driver.micromodem, read and checked once
//   micromodem_driver.cpp — the driver's lifecycle (start, stop, reboots,
//                       keep-alive) and its sending
//   micromodem_sentence_routes.cpp — each received sentence to its part
//   startup_sequence  — §4.6: revision, SRC = modem_id, NVRAM, user cfg, clock
//   command_queue     — one command at a time, echo-confirmed, retried
//   data_cycle        — $CCCYC / $CADRQ / $CCTXD / transmit reports, polls
//   reception         — $CARXP … $CACST into DATA transmissions
//   ack_tracker       — the modem's $CAACK into one ACK per packet
//   bad_input_log     — counted, logged once per burst
//   driver_specific_exchange — ping, LBL, mini-packets, FDP (spec §6-§7);
//                       its sentences are routed in micromodem_driver_specific.cpp
//   poll_frames       — how many frames a poll asks for ($CCCYC Nframes)
//   fdp_data_link     — with driver.micromodem.fdp_data (MM2): the DATA as
//                       $CCTDP / $CARDP instead of the cycle
// The DriverSequence (link/driver_sequence.h) makes the decisions every
// driver shares (data request before the cycle, polls, what on_receive
// sees); the modem acknowledges in hardware, so software_acks is off,
// except with fdp_data: FDP firmware ACKs are not to be relied on (§6).
//
// Failures the supervisor should restart the driver for (DriverError from
// do_work): a start-up that fails (no answer, a refused setting — named),
// the port lost, five commands in a row unanswered. A modem reboot is not
// one: the exchange in progress fails, the settings are applied again, and
// the driver carries on.
//
// Core thread only.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "core/scheduler.h"
#include "link/driver.h"
#include "link/driver_sequence.h"
#include "micromodem/ack_tracker.h"
#include "micromodem/bad_input_log.h"
#include "micromodem/command_queue.h"
#include "micromodem/data_cycle.h"
#include "micromodem/driver_specific_exchange.h"
#include "micromodem/fdp_data_link.h"
#include "micromodem/micromodem_settings.h"
#include "micromodem/modem_port.h"
#include "micromodem/nmea/line_framer.h"
#include "micromodem/reception.h"
#include "micromodem/startup_sequence.h"

namespace acomms::drivers::micromodem {

class MicroModemDriver final : public link::Driver {
 public:
  // Throws std::invalid_argument for a bad driver.micromodem config (named).
  MicroModemDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, std::unique_ptr<ModemPort> port);
  ~MicroModemDriver() override;

  void start(link::DriverCallbacks callbacks) override;
  void stop() override;
  void do_work() override;
  void initiate_transmission(const v1::ModemTransmission& transmission) override;
  // The slot budget's figures (link/slot_budget.h): the rate table's, with
  // its margin, on the modem's clock. A modem run time_scale times faster
  // (the fake, in tests) takes that much less time on the air and in the
  // water, so the same slots carry the same frames.
  std::chrono::nanoseconds packet_air_time(int32_t rate, uint32_t num_frames) const override;
  std::chrono::nanoseconds ack_time(int32_t rate) const override;
  double sound_speed() const override;
  // micromodem_driver_specific.cpp: ping, LBL, mini-packets, FDP.
  link::DriverSpecificResult check_driver_specific(const v1::ModemTransmission& request) const override;
  void send_driver_specific(const v1::ModemTransmission& request, double deadline_s,
                            link::DriverSpecificDone done) override;
  const DriverSpecificExchange::Counters& driver_specific_counters() const { return extras_.counters(); }
  // What the bad-input log counted (for LinkStatus).
  link::DriverCounters counters() const override;
  // "MM2 2.0.27087" once a $CAREV said so.
  std::string modem() const override;
  // The modem ACKs in hardware, but for FDP data (software ACKs, §6).
  bool acks_in_hardware() const override { return !settings_.fdp_data; }

  int32_t modem_id() const { return settings_.id; }
  // Start-up finished and no reboot since.
  bool ready() const { return ready_; }
  std::optional<ModemGeneration> generation() const { return generation_; }
  const std::string& revision() const { return revision_; }
  // Reboots of a modem that was ready (its first boot is not one).
  uint64_t reboots() const { return reboots_; }
  const BadInputLog& bad_input() const { return bad_input_; }
  const DataCycle::Counters& cycle_counters() const { return cycle_.counters(); }
  const Reception::Counters& reception_counters() const { return reception_.counters(); }
  const AckTracker::Counters& ack_counters() const { return acks_.counters(); }

 private:
  void on_bytes(std::string_view bytes);
  void on_port_state(link::TransportState state, const std::string& detail);
  void on_line(const std::string& line);
  // micromodem_sentence_routes.cpp: a sentence to the part that owns it.
  void dispatch(const ::acomms::micromodem::Sentence& sentence);
  using Route = void (*)(MicroModemDriver& driver, const ::acomms::micromodem::Sentence& sentence);
  // The data path's $CA sentences by type (REV, CYC, ...).
  static const std::unordered_map<std::string_view, Route>& routes();
  // The sentences of driver-specific exchanges; true when it took this one
  // (micromodem_driver_specific.cpp).
  bool dispatch_driver_specific(const ::acomms::micromodem::Sentence& sentence);
  void on_revision(const ::acomms::micromodem::Sentence& sentence);
  void on_cycle(const ::acomms::micromodem::Sentence& sentence);
  void on_error(const ::acomms::micromodem::Sentence& sentence);
  void answer_poll(const ::acomms::micromodem::Cycle& cycle);
  void write(const ::acomms::micromodem::Sentence& sentence);
  void begin_startup();
  void on_startup_done(const std::string& error);
  void on_reboot();
  // fdp_data on a modem known to be MM1: start-up fails naming it (true).
  bool refuse_fdp_on_mm1();
  void keep_alive();
  // The DriverSequence's Medium::send: "" or why the modem cannot take it now.
  std::string send(const v1::ModemTransmission& transmission, bool report);
  // send() with driver.micromodem.fdp_data: DATA and ACKs as FDP packets.
  std::string send_fdp(const v1::ModemTransmission& transmission, bool report);
  double now_seconds() const;
  Duration scaled(Duration d) const;
  template <typename T>
  bool parsed(const ::acomms::micromodem::Result<T>& result, const ::acomms::micromodem::Sentence& sentence);

  const MicroModemSettings settings_;  // first: every other member is built from it
  std::string label_;
  core::Scheduler& scheduler_;
  std::unique_ptr<ModemPort> port_;
  link::DriverSequence sequence_;  // holds the callbacks between start() and stop()
  ::acomms::micromodem::LineFramer framer_;
  ::acomms::micromodem::LineFramer::Counters framer_seen_;
  BadInputLog bad_input_;
  CommandQueue commands_;
  DataCycle cycle_;
  Reception reception_;
  AckTracker acks_;
  DriverSpecificExchange extras_;
  FdpDataLink fdp_;
  std::unique_ptr<StartupSequence> startup_;
  bool ready_ = false;
  bool answering_poll_ = false;  // inside answer_poll(): send() starts a polled exchange
  std::string fatal_;            // thrown as DriverError by do_work()
  std::optional<ModemGeneration> generation_;
  std::string revision_;
  uint64_t reboots_ = 0;
  core::Clock::time_point last_line_{};
};

}  // namespace acomms::drivers::micromodem
