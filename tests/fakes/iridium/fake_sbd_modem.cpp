#include "fake_sbd_modem.h"

#include <cstdio>

namespace acomms::fake_iridium {
namespace {

// Spec §4.1: the sum of the bytes, low 16 bits. Written here again (not
// taken from the driver's library) so a wrong checksum in one shows up.
uint16_t checksum(std::string_view bytes) {
  unsigned sum = 0;
  for (unsigned char c : bytes) sum += c;
  return static_cast<uint16_t>(sum);
}

// At most the first 24 bytes: a transcript is read by people.
std::string hex(std::string_view bytes) {
  std::string out;
  const bool cut = bytes.size() > 24;
  if (cut) bytes = bytes.substr(0, 24);
  char two[4];
  for (unsigned char c : bytes) {
    std::snprintf(two, sizeof two, "%02x ", c);
    out += two;
  }
  if (!out.empty()) out.pop_back();
  return cut ? out + " ..." : out;
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 32 : c);
  return s;
}

}  // namespace

FakeSbdModem::FakeSbdModem(core::Scheduler& scheduler, SbdGateway& gateway, FakeSbdConfig config)
    : scheduler_(scheduler),
      gateway_(gateway),
      config_(std::move(config)),
      start_(scheduler.clock().now()),
      momsn_(config_.momsn) {
  if (config_.auto_ring) check_gateway();
}

FakeSbdModem::~FakeSbdModem() { ++epoch_; }

void FakeSbdModem::check_gateway() {
  const int queued = gateway_.mt_queued(config_.imei);
  if (queued > mt_seen_) ring();
  mt_seen_ = queued;
  scheduler_.after(std::chrono::seconds(1), [this, epoch = epoch_] {
    if (epoch == epoch_) check_gateway();
  });
}

void FakeSbdModem::log(char direction, const std::string& text) {
  const double t = std::chrono::duration<double>(scheduler_.clock().now() - start_).count();
  char stamp[32];
  std::snprintf(stamp, sizeof stamp, "%+9.3f %c ", t, direction);
  transcript_ += stamp + text + "\n";
}

void FakeSbdModem::send(std::string_view bytes) {
  if (output_) output_(bytes);
}

void FakeSbdModem::info(const std::string& text) {
  log('<', text);
  send(verbose_ ? "\r\n" + text + "\r\n" : text + "\r\n");
}

void FakeSbdModem::ok() {
  log('<', "OK");
  send(verbose_ ? "\r\nOK\r\n" : "0\r");
}

void FakeSbdModem::error() {
  log('<', "ERROR");
  send(verbose_ ? "\r\nERROR\r\n" : "4\r");
}

void FakeSbdModem::result(int digit) { info(std::to_string(digit)); }

void FakeSbdModem::indicator(int which, int value) {
  if (indicators_ && !silent_) info("+CIEV:" + std::to_string(which) + "," + std::to_string(value));
}

void FakeSbdModem::from_host(std::string_view bytes) {
  if (silent_) return;  // rebooting: nothing is heard
  for (char c : bytes) {
    if (binary_expected_ > 0) {
      binary_byte(c);
      continue;
    }
    if (busy_) continue;  // a session runs: the host must wait for its answer
    if (c == '\n') continue;
    if (c != '\r') {
      if (line_.size() < 200) line_.push_back(c);
      continue;
    }
    std::string line = std::move(line_);
    line_.clear();
    if (echo_) send(line + "\r");  // the echo: the command and its CR
    if (!line.empty()) command(line);
  }
}

void FakeSbdModem::binary_byte(char c) {
  binary_.push_back(c);
  if (binary_.size() < binary_expected_) return;
  scheduler_.cancel(write_timer_);
  const size_t n = binary_expected_ - 2;
  binary_expected_ = 0;
  std::string payload = binary_.substr(0, n);
  const uint16_t sent = static_cast<uint16_t>(static_cast<unsigned char>(binary_[n]) << 8 |
                                              static_cast<unsigned char>(binary_[n + 1]));
  log('>', "[" + std::to_string(n) + " bytes + checksum] " + hex(binary_));
  binary_.clear();
  if (sent != checksum(payload)) {
    result(2);
  } else {
    mo_ = std::move(payload);
    result(0);
  }
  ok();
}

void FakeSbdModem::command(const std::string& raw) {
  log('>', raw);
  const std::string c = upper(raw);
  if (!c.starts_with("AT")) return error();
  const std::string body = c.substr(2);
  if (body.empty() || body == "&K0" || body == "&K3" || body == "Q0" || body == "&W0" || body == "&Y0" ||
      body == "+SBDAREG=1" || body == "+SBDAREG=0") {
    return ok();
  }
  if (body == "E0" || body == "E1") return echo_ = body == "E1", ok();
  if (body == "V0" || body == "V1") return verbose_ = body == "V1", ok();
  if (body == "*R0" || body == "*R1") return radio_ = body == "*R1", ok();
  if (body == "+SBDMTA=0" || body == "+SBDMTA=1") return ring_alerts_ = body == "+SBDMTA=1", ok();
  if (body.starts_with("+CIER=")) {
    indicators_ = body.substr(6, 1) == "1";
    ok();
    // The current values follow (as in CIERLOG).
    indicator(0, network_ ? config_.rssi : 0);
    indicator(1, network_ ? 1 : 0);
    indicator(2, antenna_fault_ ? 1 : 0);
    return;
  }
  if (body == "+CGSN") return info(config_.imei), ok();
  if (body == "+CSQ") return info("+CSQ:" + std::to_string(network_ && !antenna_fault_ ? config_.rssi : 0)), ok();
  if (body == "+SBDSX" || body == "+SBDS") {
    std::string fields = std::to_string(mo_ ? 1 : 0) + ", " + std::to_string(momsn_) + ", " +
                         std::to_string(mt_ ? 1 : 0) + ", " + std::to_string(mt_ ? mt_->mtmsn : -1);
    if (body == "+SBDS") return info("+SBDS: " + fields), ok();
    return info("+SBDSX: " + fields + ", " + std::to_string(ra_flag_ ? 1 : 0) + ", " + std::to_string(msg_waiting_)), ok();
  }
  if (body == "+SBDD0" || body == "+SBDD1" || body == "+SBDD2") {
    if (body != "+SBDD1") mo_.reset();
    if (body != "+SBDD0") mt_.reset();
    return result(0), ok();
  }
  if (body == "+SBDC") return momsn_ = 0, result(0), ok();
  if (body.starts_with("+SBDWB=")) {
    int n = std::atoi(body.c_str() + 7);
    if (n < 1 || n > 340) return result(3), ok();  // in place of READY (spec §4.1 row 3)
    binary_expected_ = static_cast<size_t>(n) + 2;
    binary_.clear();
    info("READY");
    // 60 s for the data, then result 1 and no OK (spec §4.1).
    write_timer_ = scheduler_.after(std::chrono::seconds(60), [this, epoch = epoch_] {
      if (epoch != epoch_ || binary_expected_ == 0) return;
      binary_expected_ = 0;
      binary_.clear();
      result(1);
    });
    return;
  }
  if (body == "+SBDRB") {
    const std::string payload = mt_ ? mt_->payload : "";
    const uint16_t sum = checksum(payload);
    std::string block;
    block.push_back(static_cast<char>(payload.size() >> 8));
    block.push_back(static_cast<char>(payload.size() & 0xFF));
    block += payload;
    block.push_back(static_cast<char>(sum >> 8));
    block.push_back(static_cast<char>(sum & 0xFF));
    log('<', "[MT block] " + hex(block));
    send(block);
    return ok();
  }
  if (body == "+SBDIX" || body == "+SBDIXA") return session(body == "+SBDIXA");
  error();
}

void FakeSbdModem::session(bool alert) {
  session_commands_.push_back(scheduler_.clock().now());
  const std::string prefix = alert && config_.ixa_prefix ? "+SBDIXA: " : "+SBDIX: ";
  auto refused = [&](int status) {
    info(prefix + std::to_string(status) + ", " + std::to_string(momsn_) + ", 0, 0, 0, 0");
    ok();
  };
  if (!radio_) return refused(34);
  if (antenna_fault_) return refused(33);
  if (!network_) return refused(32);
  if (forced_ > 0) {
    --forced_;
    ++sessions_;
    log('-', "(fault: the session fails with status " + std::to_string(forced_status_) + ")");
    return refused(forced_status_);
  }
  busy_ = true;
  ++sessions_;
  std::optional<std::string> mo = mo_;
  scheduler_.after(config_.session_time, [this, alert, mo, epoch = epoch_] {
    if (epoch != epoch_) return;  // rebooted mid-session: it never happened
    busy_ = false;
    finish_session(alert, mo);
  });
}

void FakeSbdModem::finish_session(bool alert, std::optional<std::string> mo) {
  const std::string prefix = alert && config_.ixa_prefix ? "+SBDIXA: " : "+SBDIX: ";
  if (hang_ > 0) {
    --hang_;
    log('-', "(fault: the session hangs; nothing sent, no answer)");
    return;
  }
  const uint16_t used = momsn_;
  if (mo && !mo->empty()) gateway_.mo_received(config_.imei, used, *mo);
  if (fail_at_gateway_ > 0) {
    --fail_at_gateway_;
    log('-', "(fault: the gateway has MOMSN " + std::to_string(used) + ", the modem is told 13)");
    info(prefix + "13, " + std::to_string(used) + ", 2, 0, 0, " + std::to_string(gateway_.mt_queued(config_.imei)));
    return ok();
  }
  // A session empties the MT buffer, then fetches the oldest MT (spec §4.6).
  mt_.reset();
  std::optional<MtMessage> mt;
  if (repeat_mt_ > 0 && last_mt_) {
    --repeat_mt_;
    mt = last_mt_;
  } else {
    mt = gateway_.take_mt(config_.imei);
  }
  if (mt) mt_ = last_mt_ = mt;
  momsn_ = static_cast<uint16_t>(momsn_ + 1);  // wraps 65535 -> 0
  ra_flag_ = false;
  msg_waiting_ = gateway_.mt_queued(config_.imei);
  if (lose_answer_ > 0) {
    --lose_answer_;
    log('-', "(fault: the session went through as MOMSN " + std::to_string(used) + "; its answer is lost)");
    return;
  }
  info(prefix + "0, " + std::to_string(used) + ", " + (mt ? "1" : "0") + ", " + std::to_string(mt ? mt->mtmsn : 0) +
       ", " + std::to_string(mt ? mt->payload.size() : 0) + ", " + std::to_string(msg_waiting_));
  ok();
}

void FakeSbdModem::set_network(bool available) {
  if (available == network_) return;
  network_ = available;
  log('-', available ? "(network back)" : "(fault: no network)");
  if (busy_) return;  // held during a session (spec §5.3); the next change shows
  indicator(0, available ? config_.rssi : 0);
  indicator(1, available ? 1 : 0);
}

void FakeSbdModem::set_antenna_fault(bool fault) {
  if (fault == antenna_fault_) return;
  antenna_fault_ = fault;
  log('-', fault ? "(fault: antenna)" : "(antenna repaired)");
  indicator(2, fault ? 1 : 0);
}

void FakeSbdModem::ring() {
  ra_flag_ = true;
  if (ring_alerts_ && !silent_) info("SBDRING");
}

void FakeSbdModem::reboot(Duration silent) {
  ++epoch_;  // a session or a write in progress dies with the power
  log('-', "(fault: reboot; silent for a while)");
  silent_ = true;
  busy_ = false;
  binary_expected_ = 0;
  line_.clear();
  echo_ = verbose_ = radio_ = true;
  ring_alerts_ = indicators_ = false;
  mo_.reset();
  mt_.reset();
  scheduler_.after(silent, [this, epoch = epoch_] {
    if (epoch != epoch_) return;
    silent_ = false;
    log('-', "(powered up)");
    if (config_.auto_ring) check_gateway();
  });
}

}  // namespace acomms::fake_iridium
