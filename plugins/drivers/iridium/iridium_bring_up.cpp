// Init and Recover (spec §3, §7): bringing the modem to a known state, and
// deciding what became of a session whose answer was lost.
//
// Init runs at every port open, after a modem reset (echo or numeric codes
// came back) and at the end of every Recover: it is idempotent, so one
// sequence serves them all. Its +SBDSX is where a lost session is decided
// (the MOMSN rule) and where an MT left in the modem (before a restart of
// the daemon, or fetched by the lost session) is read before +SBDD2 clears
// the buffers.
#include <spdlog/spdlog.h>

#include <algorithm>

#include "iridium/iridium_driver.h"

namespace acomms::drivers::iridium {

using Expect = AtChannel::Expect;
using End = AtChannel::Reply::End;

namespace {
constexpr auto kAlivePoll = std::chrono::seconds(1);     // AT once a second...
constexpr auto kAliveBudget = std::chrono::seconds(60);  // ...for a minute (spec §3)
constexpr int kInitAttempts = 3;
constexpr int kRecoverTries = 3;
constexpr auto kRecoverSpacing = std::chrono::seconds(2);
}  // namespace

void IridiumDriver::begin_init() {
  state_ = State::kInit;
  channel_.cancel();
  if (++init_attempts_ > kInitAttempts) {
    fatal_ = "the bring-up failed " + std::to_string(kInitAttempts) + " times in a row";
    return;
  }
  poll_alive(now() + kAliveBudget);
}

void IridiumDriver::poll_alive(core::Clock::time_point deadline) {
  command("AT", Expect::kFinal, kAlivePoll, [this, deadline](Reply reply) {
    if (reply.ok()) return run_init_steps(0, 0);
    if (now() >= deadline) {
      fatal_ = "no answer to AT for 60 s";
      return;
    }
    // A timed-out AT already took its second; an ERROR waits for one.
    auto wait = reply.end == End::kTimeout ? Duration::zero() : Duration(kAlivePoll);
    scheduler_.after(wait, [this, deadline, alive = std::weak_ptr<const char>(alive_)] {
      if (!alive.expired() && state_ == State::kInit && sequence_.running()) poll_alive(deadline);
    });
  });
}

void IridiumDriver::run_init_steps(size_t step, int errors) {
  // Each ends with OK (spec §3); the IMEI and the status are read on the way.
  const std::string steps[] = {"ATE0",           "ATV1",          "ATQ0",         settings_.rts_cts ? "AT&K3" : "AT&K0",
                               "AT*R1",          "AT+CIER=1,1,1,1", "AT+SBDMTA=1", "AT+SBDAREG=1",
                               "AT+CGSN"};
  if (step == std::size(steps)) {
    return init_status([this] {
      command("AT+SBDD2", Expect::kResult, settings_.command_timeout, [this](Reply reply) {
        if (!reply.ok() || reply.digit != 0) {
          spdlog::warn("{}: AT+SBDD2 not done (digit {}); bringing the modem up again", label_, reply.digit);
          return begin_init();
        }
        if (pending_) pending_->loaded = false;  // cleared with the rest
        init_attempts_ = 0;
        channel_.clear_flags();
        spdlog::info("{}: ready (IMEI {})", label_, imei_);
        // One mailbox check after bring-up: the gateway learns where to
        // ring, and a queued MT comes (spec §3).
        next_mailbox_ = now();
        idle();
      });
    });
  }
  const std::string& text = steps[step];
  command(text, Expect::kFinal, settings_.command_timeout, [this, step, errors, text](Reply reply) {
    if (reply.end == End::kTimeout) {
      spdlog::warn("{}: no answer to {} during bring-up", label_, text);
      return begin_init();
    }
    if (reply.end == End::kError) {
      // Once more after an AT; a second refusal is the modem's answer (spec §11).
      if (errors >= 1) {
        fatal_ = "the modem refused " + text + " twice";
        return;
      }
      return command("AT", Expect::kFinal, settings_.command_timeout,
                     [this, step, errors](Reply) { run_init_steps(step, errors + 1); });
    }
    if (text == "ATE0") channel_.clear_flags();  // echo so far was expected
    if (text == "AT+CGSN") return check_imei(reply, [this, step] { run_init_steps(step + 1, 0); });
    run_init_steps(step + 1, 0);
  });
}

void IridiumDriver::check_imei(const Reply& reply, Next next) {
  std::string imei;
  for (const AtLine& line : reply.lines) {
    if (line.text.size() == 15 && std::all_of(line.text.begin(), line.text.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      imei = line.text;
    }
  }
  if (imei.empty()) {
    spdlog::warn("{}: AT+CGSN gave no 15-digit IMEI", label_);
  } else if (!settings_.imei.empty() && imei != settings_.imei) {
    fatal_ = "the modem's IMEI is " + imei + ", driver.iridium.imei expects " + settings_.imei + " (wrong modem on the port?)";
    return;
  }
  imei_ = imei.empty() ? "(IMEI unknown)" : imei;
  next();
}

void IridiumDriver::init_status(Next next) {
  command("AT+SBDSX", Expect::kFinal, settings_.command_timeout, [this, next](Reply reply) {
    for (const AtLine& line : reply.lines) {
      if (line.kind == AtLine::Kind::kStatus) return resolve_status(line.status, next);
    }
    spdlog::warn("{}: AT+SBDSX gave no status", label_);
    begin_init();
  });
}

void IridiumDriver::resolve_status(const ::acomms::iridium::BufferStatus& status, Next next) {
  momsn_before_ = status.momsn;
  if (status.ra_flag == 1) ring_pending_ = true;  // an alert not yet answered
  bool delivered = false;
  if (unknown_momsn_) {
    // The MOMSN rule (spec §7 Recover): it advances only on success.
    const bool advanced = status.momsn != *unknown_momsn_;
    spdlog::warn("{}: the session at MOMSN {} lost its answer; the modem's MOMSN is now {}: {}", label_,
                 *unknown_momsn_, status.momsn,
                 advanced ? "it went through" : pending_ ? "not sent, sending again" : "nothing was sent");
    unknown_momsn_.reset();
    if (advanced && pending_) delivered = true;
    if (!advanced && pending_) ++stats_.mo_resent;
  }
  auto after_mt = [this, delivered, next] {
    if (delivered) return mo_delivered(next);
    next();
  };
  // An MT in the buffer (fetched by the lost session, or left from before
  // a restart): read it before anything clears it (spec §4.6).
  if (status.mt_flag == 1) return read_mt(status.mtmsn, -1, 0, after_mt);
  after_mt();
}

void IridiumDriver::recover(const std::string& why) {
  ++stats_.recoveries;
  spdlog::warn("{}: recovering: {}", label_, why);
  state_ = State::kInit;
  channel_.cancel();
  recover_try(0);
}

void IridiumDriver::recover_try(int tries) {
  command("AT", Expect::kFinal, kRecoverSpacing, [this, tries](Reply reply) {
    // Alive: the bring-up restores the settings and decides the session.
    if (reply.ok()) return run_init_steps(0, 0);
    if (tries + 1 < kRecoverTries) return recover_try(tries + 1);
    // Silent: as after power-up, poll it for a minute (a reset modem
    // answers again after a while; spec §11).
    begin_init();
  });
}

}  // namespace acomms::drivers::iridium
