#pragma once
// The transmit side of the Micro-Modem (spec §5.1-5.5, §8.1-8.3, §11): one
// exchange at a time, each ending in exactly one result.
//
// Kinds of exchange:
//  - local: our own DATA. The frames come from the queues *before*
//    `$CCCYC` (the DriverSequence's data request) and each `$CADRQ` is
//    answered at once from them, frame F with frame[F-1], an empty
//    `$CCTXD` past the last (spec §10 quirk 4: a slow answer misses the
//    modem's DTO). Requesting per `$CADRQ` instead would put the queues and
//    the store on the modem's clock.
//  - poll: a third-party cycle (`$CCCYC` with ADR1 = the polled node). It
//    has gone once the cycle-init mini-packet is sent; the answer arrives as
//    received DATA.
//  - polled: another node's poll for us (`$CACYC` with ADR1 = our id from
//    the water). The DriverSequence asks the queues for frames and the
//    `$CADRQ`s are answered from them, as for a local cycle, without a
//    `$CCCYC` of ours.
// States: IDLE → (`$CCCYC`) AWAIT_ECHO → SUPPLYING (`$CADRQ`/`$CCTXD`) →
// TRANSMITTING (`$CATXP`…`$CATXF`) → AWAIT_STATISTICS (`$CAXST`) → IDLE.
// Every wait has a deadline from spec §9 (scaled for a sped-up fake): an
// exchange that never completes fails, it never hangs. Failures: a refused
// or unechoed `$CCCYC`, a `$CACYC` from the water while we wait for our echo
// (the modem is receiving), `$CAERR DATA_TIMEOUT`, `$CAXST` mode ≠ 0,
// `$CAMSG Transmit aborted`, a reboot.
//
// Core thread only.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "acomms/v1/modem_transmission.pb.h"
#include "core/scheduler.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"

namespace acomms::drivers::micromodem {

struct CycleTimeouts {
  using Duration = std::chrono::system_clock::duration;
  Duration echo = std::chrono::seconds(2);           // $CCCYC → $CACYC (< 0.1 s, §9)
  Duration margin = std::chrono::seconds(2);         // serial time and slack added to each wait
  Duration statistics = std::chrono::seconds(1);     // $CATXF → $CAXST
  double max_range_m = 2000;                         // for ACK waits
  double time_scale = 1;                             // divides every wait
};

class DataCycle {
 public:
  struct Counters {
    uint64_t cycles = 0;            // $CCCYC sent
    uint64_t frames_supplied = 0;   // non-empty $CCTXD
    uint64_t unsolicited_requests = 0;  // $CADRQ with no exchange (answered empty)
    uint64_t data_timeouts = 0;     // $CAERR DATA_TIMEOUT
    uint64_t failures = 0;
  };
  struct Hooks {
    std::function<void(const ::acomms::micromodem::Sentence&)> write;
    // The exchange's result, exactly once for a reported exchange.
    std::function<void(const v1::ModemTransmission&, bool ok, const std::string& error)> report;
    // A local DATA packet has gone: ACKs may follow within `wait`.
    std::function<void(const v1::ModemTransmission&, std::chrono::system_clock::duration wait)> sent;
  };

  DataCycle(core::Scheduler& scheduler, int own_id, CycleTimeouts timeouts, Hooks hooks);
  ~DataCycle();

  // Starts our own DATA (frames filled), a poll (src ≠ own id), or the
  // answer to a poll heard (`polled`). "" or why not ("busy ...").
  std::string start(const v1::ModemTransmission& transmission, bool polled);
  bool idle() const { return phase_ == Phase::kIdle; }

  // Sentences; each returns true when it belonged to the exchange.
  bool on_cycle(const ::acomms::micromodem::Cycle& cycle);
  void on_data_request(const ::acomms::micromodem::DataRequest& request);
  void on_transmit_started(const ::acomms::micromodem::TransmitStarted& started);
  void on_transmit_finished(const ::acomms::micromodem::TransmitFinished& finished);
  void on_transmit_statistics(const ::acomms::micromodem::TransmitStatistics& statistics);
  void on_error(const ::acomms::micromodem::ModemError& error);
  void on_message(const ::acomms::micromodem::TransactionMessage& message);
  // Ends the exchange in progress as failed (a reboot, a lost port).
  void abort(const std::string& why);

  const Counters& counters() const { return counters_; }

 private:
  enum class Phase { kIdle, kAwaitEcho, kSupplying, kTransmitting, kAwaitStatistics };
  enum class Kind { kLocal, kPoll, kPolled };
  struct Exchange {
    v1::ModemTransmission transmission;
    Kind kind = Kind::kLocal;
    ::acomms::micromodem::Cycle cycle;
    int frames_supplied = 0;  // non-empty $CCTXD
    int frames_answered = 0;  // every $CCTXD
    std::string data_timeout;  // set by $CAERR DATA_TIMEOUT: the result is a failure
  };

  void wait(std::chrono::system_clock::duration duration, const std::string& what);
  void finish(bool ok, const std::string& error);
  std::chrono::system_clock::duration scaled(std::chrono::system_clock::duration d) const;
  std::chrono::system_clock::duration air_time() const;

  core::Scheduler& scheduler_;
  int own_id_;
  CycleTimeouts timeouts_;
  Hooks hooks_;
  Phase phase_ = Phase::kIdle;
  std::optional<Exchange> exchange_;
  core::Scheduler::TaskId timer_ = 0;
  Counters counters_;
};

}  // namespace acomms::drivers::micromodem
