#include "iridium/at_channel.h"

#include <spdlog/spdlog.h>

#include <chrono>

namespace acomms::drivers::iridium {

using Kind = AtLine::Kind;
using End = AtChannel::Reply::End;

namespace {
// After a result digit that may or may not be followed by OK, how long to
// wait for the OK before the digit stands alone.
constexpr auto kDigitGrace = std::chrono::seconds(1);
}  // namespace

AtChannel::AtChannel(core::Scheduler& scheduler, Write write, Unsolicited unsolicited)
    : scheduler_(scheduler), write_(std::move(write)), unsolicited_(std::move(unsolicited)) {}

AtChannel::~AtChannel() { abort(); }

void AtChannel::send(std::string bytes, std::string echo, Expect expect, Duration timeout, Done done) {
  cancel();
  ++counters_.commands;
  pending_ = Pending{std::move(echo), expect, std::move(done), {}, 0};
  if (expect == Expect::kBlock) reader_.expect_binary();
  if (!write_(bytes)) {
    arm(Duration::zero());  // ends as a timeout, outside this call
    return;
  }
  arm(timeout);
}

void AtChannel::arm(Duration timeout) {
  if (pending_->timer != 0) scheduler_.cancel(pending_->timer);
  const uint64_t generation = ++generation_;
  pending_->timer = scheduler_.after(timeout, [this, generation] {
    if (generation != generation_ || !pending_) return;
    pending_->timer = 0;
    // A digit that needed no OK after all (result 1 of +SBDWB, 3 for READY).
    if (pending_->reply.digit >= 0 && pending_->expect != Expect::kFinal) return finish(End::kDigit);
    ++counters_.timeouts;
    finish(End::kTimeout);
  });
}

void AtChannel::cancel() {
  ++generation_;
  if (pending_ && pending_->timer != 0) scheduler_.cancel(pending_->timer);
  if (pending_ && pending_->expect == Expect::kBlock) reader_.cancel_binary();
  pending_.reset();
}

void AtChannel::abort() {
  cancel();
  reader_.reset();
}

void AtChannel::on_bytes(std::string_view bytes) {
  for (auto& event : reader_.push(bytes)) {
    using EventKind = ::acomms::iridium::AtEvent::Kind;
    if (event.kind == EventKind::kLine) {
      on_line(event.line);
      continue;
    }
    if (!pending_ || pending_->expect != Expect::kBlock) {
      ++counters_.stray;
      continue;
    }
    if (event.kind == EventKind::kBlock) {
      pending_->reply.block = std::move(event.block);
    } else {
      pending_->reply.bad_block_length = event.bad_length;
    }
  }
}

void AtChannel::on_line(const AtLine& line) {
  if (line.kind == Kind::kMalformed) {
    ++counters_.malformed;
    spdlog::warn("iridium: malformed answer \"{}\" ignored", line.text);
    return;
  }
  if (line.unsolicited()) {
    if (unsolicited_) unsolicited_(line);
    return;
  }
  if (!pending_) {
    ++counters_.stray;
    spdlog::debug("iridium: line \"{}\" while no command waits", line.text);
    return;
  }
  Pending& p = *pending_;
  if (!p.echo.empty() && line.text == p.echo) {
    ++counters_.echoes;
    echo_seen_ = true;
    return;
  }
  switch (line.kind) {
    case Kind::kOk: return finish(End::kOk);
    case Kind::kError: return finish(End::kError);
    case Kind::kReady:
      if (p.expect == Expect::kReady) return finish(End::kReady);
      break;
    case Kind::kDigit:
      if (p.expect == Expect::kFinal || p.reply.digit >= 0) {
        // Numeric result codes (ATV0): "0" is OK; anything else (4
        // ERROR, 2 RING, 3 NO CARRIER, ...) is not.
        numeric_seen_ = true;
        return finish(line.digit == 0 ? End::kOk : End::kError);
      }
      p.reply.digit = line.digit;
      if (p.expect == Expect::kResult && line.digit == 1) return finish(End::kDigit);
      arm(kDigitGrace);  // OK should follow at once
      return;
    default: break;
  }
  p.reply.lines.push_back(line);
}

void AtChannel::finish(End end) {
  Pending p = std::move(*pending_);
  pending_.reset();
  ++generation_;
  if (p.timer != 0) scheduler_.cancel(p.timer);
  if (p.expect == Expect::kBlock) reader_.cancel_binary();
  p.reply.end = end;
  if (p.done) p.done(std::move(p.reply));
}

}  // namespace acomms::drivers::iridium
