#include "telemetry/stream_receiver.h"

#include <spdlog/spdlog.h>

#include <bit>
#include <limits>

#include "dccl/error.h"
#include "telemetry/state_bytes.h"

namespace acomms::telemetry {
namespace {

constexpr uint64_t kStateVersion = 2;  // 2: asked

void put_message(StateWriter& out, const WireMessage& m, double arrived) {
  out.put(static_cast<uint64_t>(m.kind), 1);
  out.put(m.sequence, 2);
  out.put(std::bit_cast<uint64_t>(arrived), 8);
  std::string bits;
  for (bool b : m.body) bits.push_back(b ? 1 : 0);
  out.put_bytes(bits);
}

}  // namespace

StreamReceiver::StreamReceiver(const TelemetryConfig& config, int32_t src, double gap_timeout_s)
    : config_(config), src_(src), gap_timeout_s_(gap_timeout_s), decoder_(config) {}

std::vector<ReceivedPosition> StreamReceiver::receive(const WireMessage& message, double now) {
  std::vector<ReceivedPosition> out;
  if (!started_) {
    // Nothing consumed yet: a full starts the stream; a delta waits for the
    // full that precedes it, if that is still on its way.
    if (message.kind == MessageKind::kFull) {
      consume(message, now, &out);
      release(now, &out);
    } else {
      // A receiver without state: the sender's next full must be fresh.
      ask_for_fresh();
      if (held_.size() < kMaxHeld) held_.emplace(message.sequence, Held{message, now});
    }
    return out;
  }
  const int32_t d = sequence_distance(message.sequence, last_);
  if (d == 1) {
    consume(message, now, &out);
  } else if (message.kind == MessageKind::kFull && !could_follow(message, d, now)) {
    // Its number says "later" or "resent" but its time says otherwise: a
    // sender that counts anew, or a late copy of an old full. Held, the
    // old one would wait out the gap timeout and then be consumed as the
    // next full: the stream would jump back to an old state.
    if (newer_than_all(message, now)) {
      start_afresh(message, d, now, &out);
    } else {
      ++counters_.duplicates;
    }
  } else if (d > 1) {
    if (held_.size() < kMaxHeld || held_.count(message.sequence)) held_.emplace(message.sequence, Held{message, now});
  } else {
    ++counters_.duplicates;
  }
  release(now, &out);
  return out;
}

bool StreamReceiver::could_follow(const WireMessage& full, int32_t d, double now) const {
  if (d <= 0) return false;
  // Samples lie on the tau grid, one message each: d messages on from the
  // last position are at least d tau later. Past half a cycle of tau
  // (also the longest ttl_s, node_settings.cpp) the number no longer tells
  // how many messages came between: d is that count modulo 4096, folded.
  const std::optional<int64_t> since = since_last(full, now);
  const int64_t tau = config_.tau_s;
  return since && *since >= int64_t{d} * tau && *since < int64_t{kWireSequenceModulus / 2} * tau;
}

std::optional<int64_t> StreamReceiver::since_last(const WireMessage& full, double now) const {
  const int64_t time = full_time(full, now);
  int64_t since = 0;
  // No time in a body too short, and no difference with a last time from
  // state bytes written elsewhere: neither follows anything.
  if (time == INT64_MIN || __builtin_sub_overflow(time, last_time_s_, &since)) return std::nullopt;
  return since;
}

bool StreamReceiver::newer_than_all(const WireMessage& full, double now) const {
  const int64_t time = full_time(full, now);
  if (time <= last_time_s_) return false;
  for (const auto& [sequence, held] : held_) {
    if (held.message.kind == MessageKind::kFull && full_time(held.message, now) >= time) return false;
  }
  return true;
}

void StreamReceiver::start_afresh(const WireMessage& full, int32_t d, double now, std::vector<ReceivedPosition>* out) {
  const uint32_t last_before = last_;
  const int64_t last_time_before = last_time_s_;
  // Held messages numbered after it are its own count's (they follow on
  // from it as usual) when either proof holds:
  // - its number is ahead by more than its time allows (could_follow): one
  //   of the old count numbered after it would have been sampled after it;
  // - they arrived after it was sampled: they were sent after it (a
  //   resent full overtaken by its own deltas). The old count's messages
  //   were all sent before its sender counted anew, so before this full.
  //   (Times on both nodes' clocks; a receiver clock behind the sender's
  //   only makes this proof fail, and those messages are dropped.)
  // The second is what holds past half a cycle of silence, where the
  // number no longer tells anything.
  std::map<uint32_t, Held> ahead;
  const bool new_count_ahead =
      d > 1 && since_last(full, now).value_or(INT64_MAX) < int64_t{d} * int64_t{config_.tau_s};
  const int64_t sampled = full_time(full, now);
  for (auto it = held_.begin(); it != held_.end();) {
    const bool ours = new_count_ahead ? sequence_distance(it->first, last_) > d
                                      : sequence_distance(it->first, full.sequence) > 0 &&
                                            it->second.arrived >= static_cast<double>(sampled);
    if (ours) {
      ahead.insert(held_.extract(it++));
    } else {
      ++it;
    }
  }
  // The rest is the old count's, all sampled before this full. The gap in
  // front of it will not fill (its sender counts anew): its held fulls and
  // the deltas that follow each are delivered now, as the gap timeout would
  // have delivered them later; the deltas with no full before them cannot
  // be decoded and are dropped.
  const uint64_t positions_before = counters_.positions;
  size_t dropped = held_.size();
  while (std::optional<uint32_t> next_full = nearest_full(std::numeric_limits<double>::infinity())) {
    ++counters_.gaps_skipped;
    for (auto next = held_.find(*next_full); next != held_.end();
         next = held_.find((last_ + 1) % kWireSequenceModulus)) {
      Held held = std::move(next->second);
      held_.erase(next);
      --dropped;
      consume(held.message, now, out);
    }
    drop_behind();
  }
  const uint64_t delivered = counters_.positions - positions_before;
  held_ = std::move(ahead);
  ++counters_.fresh_starts;
  // Once per fresh start: the one sign a person gets that a sender lost its
  // count (or was silent for half a cycle).
  spdlog::warn(
      "telemetry from {}: full {} (time {}) is newer than the last position (message {}, time {}) but its number "
      "does not follow on: the sender counts anew; continuing from it ({} held position(s) from before "
      "delivered, {} held message(s) dropped)",
      src_, full.sequence, full_time(full, now), last_before, last_time_before, delivered, dropped);
  consume(full, now, out);
}

int64_t StreamReceiver::full_time(const WireMessage& message, double now) const {
  // The time of day is the body's first 17 bits (telemetry_message.h).
  if (message.body.size() < kTimeOfDayBits) return INT64_MIN;
  int64_t time_of_day = 0;
  for (unsigned i = 0; i < kTimeOfDayBits; ++i) time_of_day |= int64_t{message.body[i]} << i;
  return unwrap_time_of_day(time_of_day, static_cast<int64_t>(now));
}

void StreamReceiver::release(double now, std::vector<ReceivedPosition>* out) {
  for (;;) {
    if (!started_) return;
    auto next = held_.find((last_ + 1) % kWireSequenceModulus);
    if (next == held_.end()) {
      std::optional<uint32_t> skip_to = nearest_full(now - gap_timeout_s_);
      if (!skip_to) break;
      next = held_.find(*skip_to);
      ++counters_.gaps_skipped;
      spdlog::warn("telemetry from {}: messages {}..{} never came within {} s: continuing from the full {}", src_,
                   (last_ + 1) % kWireSequenceModulus, (*skip_to + kWireSequenceModulus - 1) % kWireSequenceModulus,
                   gap_timeout_s_, *skip_to);
    }
    Held held = std::move(next->second);
    held_.erase(next);
    consume(held.message, now, out);
  }
  drop_behind();
}

void StreamReceiver::drop_behind() {
  // What is now behind us can never be consumed.
  for (auto it = held_.begin(); it != held_.end();) {
    it = sequence_distance(it->first, last_) <= 0 ? held_.erase(it) : std::next(it);
  }
}

std::optional<uint32_t> StreamReceiver::nearest_full(double arrived_by) const {
  std::optional<uint32_t> best;
  int32_t best_distance = 0;
  for (const auto& [sequence, held] : held_) {
    if (held.message.kind != MessageKind::kFull || held.arrived > arrived_by) continue;
    const int32_t d = started_ ? sequence_distance(sequence, last_) : 1;
    if (!best || d < best_distance) {
      best = sequence;
      best_distance = d;
    }
  }
  return best;
}

void StreamReceiver::consume(const WireMessage& message, double now, std::vector<ReceivedPosition>* out) {
  if (started_ && sequence_distance(message.sequence, last_) != 1) {
    // Past a gap: the sender's statistics include what never came.
    decoder_.restore({});
    in_step_ = false;
  }
  started_ = true;
  last_ = message.sequence;
  if (message.kind == MessageKind::kDelta && !in_step_) {
    ++counters_.out_of_step;
    ask_for_fresh();
    return;
  }
  DecodedMessage decoded;
  try {
    const std::string bytes = library_bytes(message);
    dccl::BitReader in(bytes);
    decoded = decoder_.decode(in);
    // The body must end exactly where the decoder stopped: fewer bits were
    // padding read as code, more were not part of this message. Either
    // way it was not what the sender coded.
    if (in.position() != kHeaderBits + message.body.size()) {
      undecodable(message, "the body does not end where its codeword does");
      return;
    }
  } catch (const dccl::Error& e) {
    // Bits that are not a message of this config (another config at the
    // sender, or damage).
    undecodable(message, e.what());
    return;
  } catch (const dccl::TruncatedRead&) {
    // Not derived from std::exception: the codeword's bits ended before
    // the decoder was sure of a symbol (found by telemetry_receiver_fuzz).
    undecodable(message, "the body ends inside the codeword");
    return;
  }
  if (decoded.outcome != DecodeOutcome::kPosition) {
    // The wire sequence rules out both: kept as a guard.
    ++counters_.out_of_step;
    in_step_ = false;
    return;
  }
  if (message.kind == MessageKind::kFull) {
    in_step_ = decoded.in_step;
    asked_ = false;
    if (!in_step_) {
      spdlog::info("telemetry from {}: full {} carries statistics this node does not hold: asking for a fresh one",
                   src_, message.sequence);
      ask_for_fresh();
    }
    day_offset_s_ = unwrap_time_of_day(decoded.time_s, static_cast<int64_t>(now)) - decoded.time_s;
  }
  ReceivedPosition position;
  position.src = src_;
  position.time_s = decoded.time_s + day_offset_s_;
  position.position_m = decoded.position_m;
  position.full = message.kind == MessageKind::kFull;
  last_time_s_ = position.time_s;
  ++counters_.positions;
  out->push_back(position);
}

void StreamReceiver::ask_for_fresh() {
  if (asked_) return;
  asked_ = true;
  feedback_due_ = true;
}

std::optional<Feedback> StreamReceiver::take_feedback() {
  if (!feedback_due_) return std::nullopt;
  feedback_due_ = false;
  Feedback feedback;
  if (started_) feedback.heard = last_;
  return feedback;
}

void StreamReceiver::undecodable(const WireMessage& message, const char* why) {
  ++counters_.undecodable;
  in_step_ = false;
  ask_for_fresh();
  decoder_.restore({});
  spdlog::warn("telemetry from {}: message {} does not decode ({}): waiting for the next full", src_,
               message.sequence, why);
}

std::string StreamReceiver::state() const {
  StateWriter out;
  out.put(kStateVersion, 1);
  out.put(started_ ? 1 : 0, 1);
  out.put(in_step_ ? 1 : 0, 1);
  out.put(asked_ ? 1 : 0, 1);
  out.put(last_, 2);
  out.put(static_cast<uint64_t>(day_offset_s_), 8);
  out.put(static_cast<uint64_t>(last_time_s_), 8);
  out.put_bytes(decoder_.state());
  out.put(held_.size(), 4);
  for (const auto& [sequence, held] : held_) put_message(out, held.message, held.arrived);
  return out.take();
}

bool StreamReceiver::restore(std::string_view state) {
  StateReader in(state);
  uint64_t version = 0, started = 0, in_step = 0, asked = 0, last = 0, offset = 0, last_time = 0, count = 0;
  std::string decoder_state;
  bool ok = in.get(1, &version) && version == kStateVersion && in.get(1, &started) && started <= 1 &&
            in.get(1, &in_step) && in_step <= 1 && in.get(1, &asked) && asked <= 1 && in.get(2, &last) && last < kWireSequenceModulus &&
            in.get(8, &offset) && in.get(8, &last_time) && in.get_bytes(&decoder_state) && in.get(4, &count) &&
            count <= kMaxHeld;
  std::map<uint32_t, Held> held;
  for (uint64_t i = 0; ok && i < count; ++i) {
    uint64_t kind = 0, sequence = 0, arrived = 0;
    std::string bits;
    ok = in.get(1, &kind) && kind <= 1 && in.get(2, &sequence) && sequence < kWireSequenceModulus &&
         in.get(8, &arrived) && in.get_bytes(&bits) && bits.size() <= kMaxFullBodyBits;
    if (!ok) break;
    Held h;
    h.message.kind = static_cast<MessageKind>(kind);
    h.message.src = src_;
    h.message.sequence = static_cast<uint32_t>(sequence);
    for (char b : bits) h.message.body.push_back(b != 0);
    h.arrived = std::bit_cast<double>(arrived);
    held.emplace(h.message.sequence, std::move(h));
  }
  ok = ok && in.done();
  // A decoder state that does not replay leaves the stream out of step.
  const bool decoder_ok = ok && decoder_.restore(decoder_state);
  if (!ok) {
    decoder_.restore({});
    started_ = in_step_ = asked_ = false;
    last_ = 0;
    day_offset_s_ = last_time_s_ = 0;
    held_.clear();
    return false;
  }
  started_ = started == 1;
  in_step_ = in_step == 1 && decoder_ok;
  asked_ = asked == 1;
  last_ = static_cast<uint32_t>(last);
  day_offset_s_ = static_cast<int64_t>(offset);
  last_time_s_ = static_cast<int64_t>(last_time);
  held_ = std::move(held);
  return decoder_ok;
}

}  // namespace acomms::telemetry
