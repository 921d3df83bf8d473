// The Iridium driver's lifecycle, its Idle decisions and its status (the
// states of spec §7 that are not a command sequence; those are in
// iridium_bring_up.cpp and iridium_session.cpp).
#include "iridium/iridium_driver.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <ctime>

#include "core/core_thread.h"
#include "iridium/at/sbd_binary.h"

namespace acomms::drivers::iridium {

using v1::ModemTransmission;

IridiumDriver::IridiumDriver(const v1::DriverConfig& config, core::Scheduler& scheduler, std::unique_ptr<SbdPort> port)
    : settings_(IridiumSettings::from_config(config)),
      label_("iridium modem " + std::to_string(settings_.id)),
      scheduler_(scheduler),
      port_(std::move(port)),
      sequence_({label_, settings_.id, settings_.max_mo_bytes, 1, /*software_acks=*/false},
                {[](const ModemTransmission&, bool) { return std::string("the iridium driver starts its own sessions"); }}),
      channel_(
          scheduler,
          [this](std::string_view bytes) {
            if (sequence_.callbacks().on_raw) sequence_.callbacks().on_raw(bytes, true);
            return port_->write(bytes);
          },
          [this](const AtLine& line) { on_unsolicited(line); }),
      retry_(static_cast<uint64_t>(settings_.id) * 0x9E3779B97F4A7C15ull) {}

IridiumDriver::~IridiumDriver() { stop(); }

void IridiumDriver::start(link::DriverCallbacks callbacks) {
  ACOMMS_ASSERT_CORE_THREAD();
  stop();
  sequence_.start(std::move(callbacks));
  state_ = State::kDown;
  fatal_.clear();
  port_->open(
      [this, alive = std::weak_ptr<const char>(alive_)](std::string_view bytes) {
        if (alive.expired() || !sequence_.running()) return;
        if (sequence_.callbacks().on_raw) sequence_.callbacks().on_raw(bytes, false);
        channel_.on_bytes(bytes);
      },
      [this](link::TransportState s, const std::string& detail) { on_port_state(s, detail); });
  spdlog::info("{}: on {}, shore node {}", label_, port_->name(), settings_.shore_id);
}

void IridiumDriver::stop() {
  ACOMMS_ASSERT_CORE_THREAD();
  port_->close();
  channel_.abort();
  sequence_.stop();
  state_ = State::kDown;
}

void IridiumDriver::do_work() {
  ACOMMS_ASSERT_CORE_THREAD();
  sequence_.check_running();
  if (!fatal_.empty()) throw link::DriverError(label_ + ": " + fatal_);
  maybe_start();
}

void IridiumDriver::initiate_transmission(const ModemTransmission& transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  sequence_.check_running();
  sequence_.report(transmission, false,
                   "the iridium driver starts its own sessions: configure mac { name: \"none\" } for this link");
}

void IridiumDriver::on_port_state(link::TransportState s, const std::string& detail) {
  if (s == link::TransportState::kOpen) {
    spdlog::info("{}: port {} open", label_, detail);
    return begin_init();
  }
  if (s == link::TransportState::kOpening) return;
  // The port is gone: whatever was in flight has an unknown outcome, and
  // the modem's buffers are not to be trusted when it comes back.
  spdlog::warn("{}: port lost ({}); the modem is brought up again when it returns", label_, detail);
  channel_.abort();
  if (session_in_flight_) unknown_momsn_ = momsn_before_;
  session_in_flight_ = false;
  if (pending_) pending_->loaded = false;
  state_ = State::kDown;
}

void IridiumDriver::on_unsolicited(const AtLine& line) {
  using Kind = AtLine::Kind;
  if (line.kind == Kind::kRing) {
    ++stats_.ring_alerts;
    ring_pending_ = true;
    spdlog::info("{}: ring alert: an MT waits at the gateway", label_);
    return;
  }
  if (line.kind == Kind::kIndicator) {
    const auto& [indicator, value] = line.indicator;
    if (indicator == 0) rssi_ = value;
    if (indicator == 1) {
      bool was = service_;
      service_ = value == 1;
      // Surfacing: one mailbox check when service returns (spec §5.2, §11).
      if (service_ && !was) next_mailbox_ = now();
    }
    if (indicator == 2) {
      antenna_fault_ = value == 1;
      if (antenna_fault_) spdlog::error("{}: the modem reports an antenna fault", label_);
    }
  }
}

void IridiumDriver::command(const std::string& text, AtChannel::Expect expect, Duration timeout,
                            std::function<void(Reply)> done) {
  channel_.send(text + "\r", text, expect, timeout,
                [this, alive = std::weak_ptr<const char>(alive_), done = std::move(done)](Reply reply) {
                  if (alive.expired() || !sequence_.running()) return;
                  done(std::move(reply));
                });
}

void IridiumDriver::idle() {
  state_ = State::kIdle;
  maybe_start();
}

void IridiumDriver::maybe_start() {
  if (state_ != State::kIdle || channel_.busy() || !sequence_.running()) return;
  const auto t = now();
  // The modem lost its settings (a reset): echo is back, or numeric codes.
  if (channel_.echo_seen() || channel_.numeric_seen()) {
    ++stats_.resets;
    spdlog::warn("{}: the modem {} since bring-up: it was reset; bringing it up again", label_,
                 channel_.echo_seen() ? "echoes commands" : "answers in numeric codes");
    if (pending_) pending_->loaded = false;  // a reset empties the MO buffer
    return begin_init();
  }
  if (t < not_before_) return;
  if (radio_off_) {
    state_ = State::kBusy;
    return command("AT*R1", AtChannel::Expect::kFinal, settings_.command_timeout, [this](Reply reply) {
      radio_off_ = !reply.ok();
      // A modem that will not turn its radio on is asked again after the
      // back-off, never in a tight loop.
      if (radio_off_) back_off(std::chrono::milliseconds(0), "AT*R1 (radio on) was refused");
      idle();
    });
  }
  if (!service_) {
    // No network: no session until the modem says service is back
    // (+CIEV:1,1) or a signal reading shows it (spec §11).
    if (t < next_signal_poll_) return;
    next_signal_poll_ = t + std::chrono::seconds(30);
    state_ = State::kBusy;
    return command("AT+CSQ", AtChannel::Expect::kFinal, 3 * settings_.command_timeout, [this](Reply reply) {
      for (const AtLine& line : reply.lines) {
        if (line.kind == AtLine::Kind::kSignal) {
          rssi_ = line.rssi;
          if (rssi_ >= 1) {
            service_ = true;
            next_mailbox_ = now();
          }
        }
      }
      idle();
    });
  }
  if (!pending_ && (ask_now_ || ring_pending_ || t >= next_send_check_)) {
    ask_now_ = false;
    next_send_check_ = t + settings_.send_check;
    ask_queues();
  }
  if (pending_) return pending_->loaded ? start_session() : write_mo();
  if (ring_pending_ || (follow_up_ && t >= follow_up_at_) || t >= next_mailbox_) return start_session();
}

bool IridiumDriver::ask_queues() {
  const auto& callbacks = sequence_.callbacks();
  if (!callbacks.on_data_request) return false;
  ModemTransmission tx;
  tx.set_type(ModemTransmission::DATA);
  tx.set_src(settings_.id);
  tx.set_dest(settings_.shore_id);
  tx.set_rate(0);
  tx.set_max_num_frames(1);
  tx.set_max_frame_bytes(settings_.max_mo_bytes);
  tx.set_ack_requested(true);
  tx.set_time(now_seconds());
  callbacks.on_data_request(&tx);
  // The link answers "nothing" with one empty frame (a slot's broadcast
  // beacon): on a paid link that is no reason for a session.
  if (tx.frame_size() == 0 || tx.frame(0).empty()) return false;
  if (tx.frame_size() > 1 || tx.frame(0).size() > settings_.max_mo_bytes) {
    spdlog::error("{}: the queues gave {} frame(s), the first of {} bytes; at most 1 of {} fits an MO", label_,
                  tx.frame_size(), tx.frame(0).size(), settings_.max_mo_bytes);
    sequence_.report(tx, false, "frames do not fit an MO");
    return false;
  }
  pending_ = PendingMo{std::move(tx), false, 0};
  return true;
}

link::DriverCounters IridiumDriver::counters() const {
  link::DriverCounters out;
  const auto& r = channel_.reader_counters();
  const auto& c = channel_.counters();
  auto put = [&out](const char* kind, uint64_t n) {
    if (n > 0) out.bad_input[kind] = n;
  };
  put("garbled line", r.garbled_lines);
  put("over-long line", r.overlong_lines);
  put("bad MT checksum", r.bad_checksums);
  put("bad MT length", r.bad_lengths);
  put("MT read again", stats_.mt_bad_reads);
  put("malformed answer", c.malformed);
  put("stray line", c.stray);
  put("command timeout", c.timeouts);
  return out;
}

std::string IridiumDriver::modem() const {
  if (imei_.empty()) return "";
  std::string out = "Iridium SBD " + imei_ + ": signal " + (rssi_ < 0 ? std::string("?") : std::to_string(rssi_)) +
                    "/5, " + (service_ ? "service" : "no service");
  if (antenna_fault_) out += ", antenna fault";
  if (!fault_.empty()) out += ", fault: " + fault_;
  if (last_.time > 0) {
    std::time_t at = static_cast<std::time_t>(std::floor(last_.time));
    char when[32];
    std::tm tm{};
    gmtime_r(&at, &tm);
    std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &tm);
    const auto& r = last_.result;
    out += std::string("; last session ") + when + ": MO status " + std::to_string(r.mo_status) + " (" +
           classify_mo_status(r.mo_status).meaning + (last_.carried_mo ? "" : ", mailbox check") + "), MOMSN " +
           std::to_string(r.momsn) + ", MT status " + std::to_string(r.mt_status) + ", " +
           std::to_string(r.mt_queued) + " MT queued";
  }
  out += "; sessions " + std::to_string(stats_.sessions) + " (" + std::to_string(stats_.sessions_failed) +
         " failed, " + std::to_string(stats_.sessions_lost) + " lost)";
  return out;
}

double IridiumDriver::now_seconds() const { return scheduler_.clock().now_seconds(); }
core::Clock::time_point IridiumDriver::now() const { return scheduler_.clock().now(); }

}  // namespace acomms::drivers::iridium
