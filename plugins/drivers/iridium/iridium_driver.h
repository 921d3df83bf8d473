#pragma once
// "iridium": the vehicle's Iridium SBD modem (a 9602/9603, bare or in a
// RockBLOCK) over its serial AT interface (/work/shared/spec/iridium-sbd.md).
//
// The problem: a satellite modem is not a slotted acoustic link. It holds
// one MO and one MT, a session (AT+SBDIX) takes tens of seconds and may
// fail, hang, or lose its answer after the gateway already has the MO; MTs
// wait at the gateway until a session fetches them. The MAC has nothing to
// schedule (mac "none"): the driver starts its own sessions (spec §7):
//   - when the queues have something: it asks them itself (on_data_request,
//     one frame of up to max_mo_bytes, destination shore_id; the queues pack
//     several DCCL messages into it) every send_check_s, at once after a
//     success, and when a ring alert (SBDRING) arrives;
//   - for a ring alert (AT+SBDIXA), for MTs still queued at the gateway
//     (3 s after the session that said so), and every mailbox_check_s;
//   - never while the retry schedule (session_retry.h) or a status's own
//     wait (mo_status.h) holds it back, nor while the modem reports no
//     service (it polls AT+CSQ then).
// A session that succeeds acknowledges its frame: the driver reports an ACK
// from shore_id for it through on_receive, as a software ACK would, so the
// queues forget what the gateway has. A failure leaves the frame in the
// modem and in the queues' flight; the retry is another AT+SBDIX.
// A session whose answer is lost (time-out, reset, port lost) is decided by
// the MOMSN (spec §7 Recover): advanced => it went (acknowledged, not
// resent); not advanced => resent, and a copy the gateway already had is
// removed by the shore's dedup and the receiver's duplicate window.
// MTs are read (AT+SBDRB, checksum and length checked, read again on a
// mismatch) and reported as DATA from shore_id; a repeated MTMSN is dropped
// (mtmsn_window.h). No software ACKs go back over the satellite: bytes there
// cost money, and the shore's endpoint learns delivery from the gateway.
//
// Split by concept: at_channel (one command at a time), iridium_bring_up.cpp
// (Init and Recover), iridium_session.cpp (Write, Session, Result, Read),
// iridium_driver.cpp (lifecycle, the Idle decisions, status).
//
// Failures the supervisor restarts the driver for (DriverError from
// do_work): no answer to AT for 60 s, a command of the bring-up refused
// twice, the wrong IMEI. Core thread only.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "acomms/v1/config.pb.h"
#include "core/scheduler.h"
#include "iridium/at_channel.h"
#include "iridium/iridium_settings.h"
#include "iridium/mo_status.h"
#include "iridium/mtmsn_window.h"
#include "iridium/sbd_port.h"
#include "iridium/session_retry.h"
#include "link/driver.h"
#include "link/driver_sequence.h"

namespace acomms::drivers::iridium {

struct IridiumStats {
  uint64_t sessions = 0;         // +SBDIX answers
  uint64_t sessions_failed = 0;  // with a failure MO status
  uint64_t sessions_lost = 0;    // no answer in time: decided by the MOMSN
  uint64_t mailbox_checks = 0;   // sessions with an empty MO buffer
  uint64_t mo_sent = 0;          // MOs the gateway has (by status or by MOMSN)
  uint64_t mo_resent = 0;        // lost answers whose MOMSN had not moved
  uint64_t mo_dropped = 0;       // frames given back after a permanent error
  uint64_t mt_delivered = 0;
  uint64_t mt_duplicates = 0;    // repeated MTMSN, dropped
  uint64_t mt_bad_reads = 0;     // checksum or length wrong (read again)
  uint64_t ring_alerts = 0;
  uint64_t recoveries = 0;       // Recover runs
  uint64_t resets = 0;           // the modem lost its settings (echo back, numeric codes)
};

// The last session, for link status.
struct LastSession {
  double time = 0;  // seconds since the epoch; 0: none yet
  ::acomms::iridium::SessionResult result;
  bool carried_mo = false;
};

class IridiumDriver final : public link::Driver {
 public:
  // Throws std::invalid_argument for a bad driver.iridium config (named).
  IridiumDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, std::unique_ptr<SbdPort> port);
  ~IridiumDriver() override;

  void start(link::DriverCallbacks callbacks) override;
  void stop() override;
  void do_work() override;
  // The MAC has no slots to give this link (mac "none"); a MAC that asks
  // anyway is told the driver starts its own sessions.
  void initiate_transmission(const v1::ModemTransmission& transmission) override;
  // No air time a slot must hold: sessions are the driver's own.
  std::chrono::nanoseconds packet_air_time(int32_t, uint32_t) const override { return {}; }
  std::chrono::nanoseconds ack_time(int32_t) const override { return {}; }
  double sound_speed() const override { return 0; }
  // Bad input by kind ("garbled line", "malformed answer", "bad MT checksum", ...).
  link::DriverCounters counters() const override;
  // "Iridium 300234010000001: signal 3/5, service; last session ...".
  std::string modem() const override;
  // An MT message is the gateway's to deliver once sent: no software ACK.
  bool acks_in_hardware() const override { return true; }

  bool ready() const { return state_ == State::kIdle || state_ == State::kBusy; }
  const IridiumStats& stats() const { return stats_; }
  const LastSession& last_session() const { return last_; }
  int rssi() const { return rssi_; }
  const std::string& imei() const { return imei_; }

 private:
  enum class State { kDown, kInit, kIdle, kBusy };
  using Reply = AtChannel::Reply;
  using Next = std::function<void()>;

  // iridium_driver.cpp
  void on_port_state(link::TransportState state, const std::string& detail);
  void on_unsolicited(const AtLine& line);
  void command(const std::string& text, AtChannel::Expect expect, Duration timeout,
               std::function<void(Reply)> done);
  void idle();          // back to Idle, and see what to start
  void maybe_start();   // the Idle decisions
  bool ask_queues();    // a frame into pending_; true if there is one
  double now_seconds() const;
  core::Clock::time_point now() const;

  // iridium_bring_up.cpp
  void begin_init();
  void poll_alive(core::Clock::time_point deadline);
  void run_init_steps(size_t step, int errors);
  void check_imei(const Reply& reply, Next next);
  void init_status(Next next);
  void resolve_status(const ::acomms::iridium::BufferStatus& status, Next next);
  void recover(const std::string& why);
  void recover_try(int tries);

  // iridium_session.cpp
  void write_mo();
  void write_block();
  void start_session();
  void on_session(const ::acomms::iridium::SessionResult& result);
  void on_session_failure(const ::acomms::iridium::SessionResult& result, const MoOutcome& outcome);
  void mo_delivered(Next next);
  void give_back_frame(const std::string& why, Next next);
  void read_mt(int mtmsn, int length, int tries, Next next);
  void deliver_mt(int mtmsn, const std::string& payload);
  void back_off(std::chrono::milliseconds least, const std::string& why);

  struct PendingMo {
    v1::ModemTransmission transmission;  // as the queues filled it
    bool loaded = false;                 // the modem's MO buffer holds it
    int write_tries = 0;
  };

  const IridiumSettings settings_;
  std::string label_;
  core::Scheduler& scheduler_;
  std::unique_ptr<SbdPort> port_;
  link::DriverSequence sequence_;  // holds the callbacks between start() and stop()
  AtChannel channel_;
  SessionRetry retry_;
  MtmsnWindow mtmsns_;
  State state_ = State::kDown;
  std::string fatal_;  // thrown as DriverError by do_work()
  int init_attempts_ = 0;
  std::string imei_;

  std::optional<PendingMo> pending_;
  // The MOMSN before the session in flight, and before one whose answer was
  // lost (decided at the next +SBDSX).
  int momsn_before_ = -1;
  std::optional<int> unknown_momsn_;
  bool session_in_flight_ = false;

  core::Clock::time_point not_before_{};    // back-off: no session before
  core::Clock::time_point next_send_check_{};
  core::Clock::time_point next_mailbox_{};
  core::Clock::time_point next_signal_poll_{};
  core::Clock::time_point follow_up_at_{};  // MTs still queued at the gateway
  bool follow_up_ = false;
  bool ask_now_ = false;       // after a success: the queues may have more
  bool ring_pending_ = false;
  bool service_ = true;        // false after +CIEV:1,0 or status 32
  bool antenna_fault_ = false;
  bool radio_off_ = false;
  int rssi_ = -1;
  std::string fault_;          // the last fault status, for link status
  LastSession last_;
  IridiumStats stats_;
  std::shared_ptr<const char> alive_ = std::make_shared<const char>(0);
};

}  // namespace acomms::drivers::iridium
