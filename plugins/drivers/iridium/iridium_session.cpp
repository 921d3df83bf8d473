// Write, Session, Result and Read (spec §7): one MO through the modem, the
// session's answer through the MO status table, and the MT it brought.
#include <spdlog/spdlog.h>

#include <algorithm>

#include "iridium/at/sbd_binary.h"
#include "iridium/iridium_driver.h"

namespace acomms::drivers::iridium {

using Expect = AtChannel::Expect;
using End = AtChannel::Reply::End;
using v1::ModemTransmission;
using ::acomms::iridium::SessionResult;

namespace {
constexpr int kWriteTries = 3;  // spec §7 Write: rewrite at most 3 times
constexpr int kReadTries = 3;
// +SBDWB: the modem waits 60 s for the data before answering 1 (spec §4.1).
constexpr auto kWriteResultTimeout = std::chrono::seconds(65);
constexpr auto kFollowUp = std::chrono::seconds(3);  // MTs still queued (spec §6.3)
}  // namespace

void IridiumDriver::write_mo() {
  state_ = State::kBusy;
  const std::string& payload = pending_->transmission.frame(0);
  if (++pending_->write_tries > kWriteTries) {
    return give_back_frame("the modem did not take it in " + std::to_string(kWriteTries) + " writes", [this] {
      recover("repeated +SBDWB failures: check the serial line (baud, noise, levels)");
    });
  }
  const std::string text = "AT+SBDWB=" + std::to_string(payload.size());
  command(text, Expect::kReady, settings_.command_timeout, [this](Reply reply) {
    if (reply.end == End::kReady) return write_block();
    if (reply.digit == 3) {
      // The frame's size is outside 1..340: the frame builder's bug, never a retry.
      return give_back_frame("the modem refused its size (+SBDWB result 3)", [this] { idle(); });
    }
    // No READY: Recover, then rewrite (spec §11).
    recover(reply.end == End::kError ? "+SBDWB answered ERROR" : "no READY after +SBDWB");
  });
}

void IridiumDriver::write_block() {
  const std::string block = ::acomms::iridium::sbdwb_block(pending_->transmission.frame(0));
  // Binary data is never echoed (spec §2): no echo text. All n+2 bytes in one write.
  channel_.send(block, "", Expect::kResult, kWriteResultTimeout,
                [this, alive = std::weak_ptr<const char>(alive_)](Reply reply) {
                  if (alive.expired() || !sequence_.running()) return;
                  if (reply.digit == 0) {
                    pending_->loaded = true;
                    pending_->write_tries = 0;
                    return start_session();
                  }
                  if (reply.digit == 1 || reply.digit == 2) {
                    spdlog::warn("{}: +SBDWB result {} ({}); writing again", label_, reply.digit,
                                 reply.digit == 1 ? "write timeout" : "checksum mismatch");
                    return reply.digit == 1 ? recover("+SBDWB write timeout") : write_mo();
                  }
                  if (reply.digit == 3) return give_back_frame("+SBDWB result 3 (size)", [this] { idle(); });
                  recover("no result after the +SBDWB data");
                });
}

void IridiumDriver::start_session() {
  state_ = State::kBusy;
  // The MOMSN before the session: if its answer is lost, the next +SBDSX
  // tells whether it went (spec §7 Session).
  command("AT+SBDSX", Expect::kFinal, settings_.command_timeout, [this](Reply reply) {
    const AtLine* status = nullptr;
    for (const AtLine& line : reply.lines) {
      if (line.kind == AtLine::Kind::kStatus) status = &line;
    }
    if (!reply.ok() || status == nullptr) return recover("no +SBDSX status before the session");
    momsn_before_ = status->status.momsn;
    if (pending_ && pending_->loaded && status->status.mo_flag == 0) {
      // The MO buffer is empty although we loaded it: the modem was reset.
      pending_->loaded = false;
      return idle();
    }
    const bool answer_alert = ring_pending_ || status->status.ra_flag == 1;
    session_in_flight_ = true;
    if (!pending_) ++stats_.mailbox_checks;
    command(answer_alert ? "AT+SBDIXA" : "AT+SBDIX", Expect::kFinal, settings_.session_timeout, [this](Reply reply) {
      session_in_flight_ = false;
      for (const AtLine& line : reply.lines) {
        if (line.kind == AtLine::Kind::kSession) return on_session(line.session);
      }
      if (reply.end == End::kError) {
        // Refused before it began: nothing was sent.
        back_off(std::chrono::milliseconds(0), "the session command answered ERROR");
        return idle();
      }
      // No answer: the outcome is unknown until the MOMSN says (Recover).
      ++stats_.sessions_lost;
      unknown_momsn_ = momsn_before_;
      back_off(std::chrono::milliseconds(0), "the session's answer was lost");
      recover("no +SBDIX answer within " +
              std::to_string(std::chrono::duration_cast<std::chrono::seconds>(settings_.session_timeout).count()) + " s");
    });
  });
}

void IridiumDriver::on_session(const SessionResult& r) {
  ++stats_.sessions;
  last_ = {now_seconds(), r, pending_.has_value()};
  next_mailbox_ = now() + settings_.mailbox_check;
  const MoOutcome outcome = classify_mo_status(r.mo_status);
  if (r.mt_status != 2) ring_pending_ = false;  // the alert is answered
  follow_up_ = r.mt_queued > 0;
  follow_up_at_ = now() + kFollowUp;
  if (r.mo_status == 1) spdlog::error("{}: the shore queued an MT over 270 bytes; this modem cannot take it", label_);
  // What the MT brought comes first: the next session would empty the buffer.
  auto then = [this, r, outcome] {
    if (outcome.action == MoAction::kSuccess) {
      retry_.reset();
      fault_.clear();
      if (pending_) return mo_delivered([this] { idle(); });
      return idle();
    }
    on_session_failure(r, outcome);
  };
  if (r.mt_status == 1) return read_mt(r.mtmsn, r.mt_length, 0, then);
  then();
}

void IridiumDriver::on_session_failure(const SessionResult& r, const MoOutcome& outcome) {
  ++stats_.sessions_failed;
  const std::string why = "MO status " + std::to_string(r.mo_status) + " (" + outcome.meaning + ")";
  if (pending_) sequence_.report(pending_->transmission, false, "session failed: " + why);
  switch (outcome.action) {
    case MoAction::kDropFrame:
      back_off(outcome.wait, why);
      return give_back_frame(why, [this] { idle(); });
    case MoAction::kFault:
    case MoAction::kAntennaFault:
      fault_ = why;
      spdlog::error("{}: {}: retrying in {} s", label_, why, outcome.wait.count());
      break;
    case MoAction::kWaitService: service_ = false; break;
    case MoAction::kRadioOff: radio_off_ = true; break;
    default: break;
  }
  back_off(outcome.wait, why);
  idle();
}

void IridiumDriver::back_off(std::chrono::milliseconds least, const std::string& why) {
  auto wait = std::max(retry_.next(), least);
  not_before_ = now() + wait;
  spdlog::info("{}: {}; next session in {:.1f} s (failure {} in a row)", label_, why,
               std::chrono::duration<double>(wait).count(), retry_.failures());
}

void IridiumDriver::mo_delivered(Next next) {
  ModemTransmission tx = std::move(pending_->transmission);
  pending_.reset();
  ++stats_.mo_sent;
  retry_.reset();
  ask_now_ = true;  // the queues may hold more than one MO's worth
  // A success leaves the MO in the buffer: clear it, or the next mailbox
  // check sends it again (spec §4.6).
  command("AT+SBDD0", Expect::kResult, settings_.command_timeout, [this, next](Reply reply) {
    if (!reply.ok() || reply.digit != 0) {
      spdlog::warn("{}: AT+SBDD0 after a success not done; bringing the modem up again (its +SBDD2 clears it)", label_);
      return begin_init();
    }
    next();
  });
  // The gateway has it: the queues forget it, as after an ACK.
  if (tx.ack_requested() && sequence_.callbacks().on_receive) {
    ModemTransmission ack;
    ack.set_type(ModemTransmission::ACK);
    ack.set_src(settings_.shore_id);
    ack.set_dest(settings_.id);
    ack.set_time(now_seconds());
    ack.add_acked_frame(0);
    sequence_.callbacks().on_receive(ack);
  }
  sequence_.report(tx, true, "");
}

void IridiumDriver::give_back_frame(const std::string& why, Next next) {
  ++stats_.mo_dropped;
  ModemTransmission tx = std::move(pending_->transmission);
  pending_.reset();
  spdlog::error("{}: MO of {} bytes not sent: {}; its messages stay queued", label_, tx.frame(0).size(), why);
  sequence_.report(tx, false, why);
  command("AT+SBDD0", Expect::kResult, settings_.command_timeout, [next](Reply) { next(); });
}

void IridiumDriver::read_mt(int mtmsn, int length, int tries, Next next) {
  state_ = State::kBusy;
  command("AT+SBDRB", Expect::kBlock, settings_.command_timeout, [this, mtmsn, length, tries, next](Reply reply) {
    std::string problem;
    if (!reply.block) {
      problem = reply.bad_block_length > 0 ? "length " + std::to_string(reply.bad_block_length) + " over 270"
                                           : "no block";
    } else if (!reply.block->checksum_ok) {
      problem = "checksum mismatch";
    } else if (length >= 0 && reply.block->payload.size() != static_cast<size_t>(length)) {
      problem = std::to_string(reply.block->payload.size()) + " bytes, the session said " + std::to_string(length);
    }
    if (problem.empty()) {
      deliver_mt(mtmsn, reply.block->payload);
      return next();
    }
    ++stats_.mt_bad_reads;
    // The buffer is kept until the next session: read it again (spec §4.3).
    if (tries + 1 < kReadTries) {
      spdlog::warn("{}: MT {} read garbled ({}); reading again", label_, mtmsn, problem);
      return read_mt(mtmsn, length, tries + 1, next);
    }
    spdlog::error("{}: MT {} lost: {} in {} reads (serial line?)", label_, mtmsn, problem, kReadTries);
    next();
  });
}

void IridiumDriver::deliver_mt(int mtmsn, const std::string& payload) {
  if (payload.empty()) return;  // an empty buffer (00 00 00 00)
  if (!mtmsns_.admit(mtmsn, payload)) {
    ++stats_.mt_duplicates;
    spdlog::info("{}: MT {} again (MTMSN and payload already delivered): dropped", label_, mtmsn);
    return;
  }
  ++stats_.mt_delivered;
  ModemTransmission rx;
  rx.set_type(ModemTransmission::DATA);
  rx.set_src(settings_.shore_id);
  rx.set_dest(settings_.id);
  rx.set_time(now_seconds());
  rx.set_ack_requested(false);  // acknowledged by the gateway, not by us
  rx.set_link_quality("iridium MTMSN " + std::to_string(mtmsn) + ", rssi " + std::to_string(rssi_));
  rx.add_frame(payload);
  sequence_.on_received(rx);
}

}  // namespace acomms::drivers::iridium
