#pragma once
// A fake Iridium 9603 for driver tests: the serial AT side of
// /work/shared/spec/iridium-sbd.md, and nothing of the radio but the
// outcomes a driver must survive.
//
// What it speaks (spec §2-§5): echo (on until ATE0, back on after a
// reboot), verbose or numeric result codes (ATV1/ATV0), the bring-up
// commands, +CGSN, +CSQ, +CIER/+CIEV, +SBDMTA ring alerts (SBDRING),
// +SBDWB (READY, n bytes + checksum, results 0/1/2/3, no OK after 1),
// +SBDRB (length, payload, checksum, then OK), +SBDD0/1/2, +SBDS, +SBDSX,
// +SBDC and +SBDIX/+SBDIXA sessions against an SbdGateway (sbd_gateway.h):
// the MO goes to the gateway, the oldest MT comes back, the MOMSN counts
// up on success only and is kept across reboots, any started session
// empties the MT buffer, a success does not empty the MO buffer.
//
// Faults, each switched on by a test: no network (status 32, +CIEV:1,0),
// antenna fault (33, +CIEV:2,1), radio off (34), a session that hangs (no
// answer, nothing sent), a session whose answer is lost after the gateway
// got the MO (the MOMSN advanced), a session that reports 13 although the
// gateway got the MO (the MOMSN does not advance: the retry duplicates it,
// as spec §5.1's "dup?" column says can happen), an MT offered again with
// its MTMSN, and a reboot (silent for a while; echo, codes, ring alerts and
// buffers back to power-up; the MOMSN kept).
//
// Everything runs on the scheduler given (a simulated one in unit tests, a
// real one in tcp_modem_host.h); output goes to set_output's function.
// Thread-safety: none; one thread (the scheduler's) drives it.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/scheduler.h"
#include "sbd_gateway.h"

namespace acomms::fake_iridium {

using Duration = std::chrono::system_clock::duration;

struct FakeSbdConfig {
  std::string imei = "300234010000001";
  uint16_t momsn = 41;                            // the next session's MOMSN (non-volatile)
  Duration session_time = std::chrono::seconds(20);  // one +SBDIX, start to answer (spec §6.2)
  int rssi = 3;                                   // bars while the network is there
  // Answer +SBDIXA with "+SBDIXA:" (true) or "+SBDIX:" (spec §12: both exist).
  bool ixa_prefix = true;
  // Ring (SBDRING) when the gateway's MT queue grows, checked every second.
  bool auto_ring = false;
};

class FakeSbdModem {
 public:
  FakeSbdModem(core::Scheduler& scheduler, SbdGateway& gateway, FakeSbdConfig config = {});
  ~FakeSbdModem();
  FakeSbdModem(const FakeSbdModem&) = delete;
  FakeSbdModem& operator=(const FakeSbdModem&) = delete;

  void set_output(std::function<void(std::string_view)> output) { output_ = std::move(output); }
  // Bytes from the host (the driver's writes).
  void from_host(std::string_view bytes);

  // Faults and events.
  void set_network(bool available);
  void set_antenna_fault(bool fault);
  void hang_sessions(int n) { hang_ += n; }             // no answer; nothing sent
  void lose_answers(int n) { lose_answer_ += n; }       // all done, answer never sent
  void fail_at_gateway(int n) { fail_at_gateway_ += n; }  // status 13, the gateway has the MO
  void repeat_mts(int n) { repeat_mt_ += n; }           // the last MT offered again
  // The next n sessions answer MO status `code` at once, nothing sent (a
  // gateway's refusal: 11, 12, 14, 15, 35, 36, 37, ...).
  void force_status(int code, int n) { forced_status_ = code, forced_ += n; }
  void stop_forcing() { forced_ = 0; }
  void reboot(Duration silent);                         // power-up after `silent`
  void ring();                                          // a ring alert, if enabled

  uint16_t momsn() const { return momsn_; }
  bool echo() const { return echo_; }
  int sessions() const { return sessions_; }
  // When each +SBDIX/+SBDIXA command arrived, answered or not.
  const std::vector<core::Clock::time_point>& session_commands() const { return session_commands_; }
  // Every exchange, one per line ("+12.000 > AT+SBDIX", "+32.000 < +SBDIX: ...").
  const std::string& transcript() const { return transcript_; }

 private:
  void command(const std::string& line);
  void binary_byte(char c);
  void session(bool alert);
  void finish_session(bool alert, std::optional<std::string> mo);
  void info(const std::string& text);
  void ok();
  void error();
  void result(int digit);  // an SBD result digit as an information line
  void send(std::string_view bytes);
  void log(char direction, const std::string& text);
  void indicator(int which, int value);
  void check_gateway();
  bool alive() const { return !silent_ && !busy_; }

  core::Scheduler& scheduler_;
  SbdGateway& gateway_;
  FakeSbdConfig config_;
  std::function<void(std::string_view)> output_;
  const core::Clock::time_point start_;

  // Volatile settings (power-up values).
  bool echo_ = true;
  bool verbose_ = true;
  bool ring_alerts_ = false;  // +SBDMTA (RockBLOCK ships with 0)
  bool indicators_ = false;   // +CIER mode 1
  bool radio_ = true;
  // Buffers (lost at power-off) and the MOMSN (kept).
  std::optional<std::string> mo_;
  std::optional<MtMessage> mt_;
  std::optional<MtMessage> last_mt_;  // for repeat_mts
  uint16_t momsn_;
  bool ra_flag_ = false;
  int msg_waiting_ = 0;
  // The radio.
  bool network_ = true;
  bool antenna_fault_ = false;
  int hang_ = 0, lose_answer_ = 0, fail_at_gateway_ = 0, repeat_mt_ = 0, forced_ = 0, forced_status_ = 0;
  // Input.
  std::string line_;
  size_t binary_expected_ = 0;  // > 0: reading +SBDWB data (payload + 2)
  std::string binary_;
  core::Scheduler::TaskId write_timer_ = 0;
  bool busy_ = false;    // a session is running
  bool silent_ = false;  // rebooting
  uint64_t epoch_ = 0;   // bumps at reboot: stale timers do nothing
  int sessions_ = 0;
  std::vector<core::Clock::time_point> session_commands_;
  int mt_seen_ = 0;      // auto_ring: the gateway's queue last time
  std::string transcript_;
};

}  // namespace acomms::fake_iridium
