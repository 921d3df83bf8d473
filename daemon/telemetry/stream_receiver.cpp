#include "telemetry/stream_receiver.h"

#include <spdlog/spdlog.h>

#include <bit>

#include "dccl/error.h"
#include "telemetry/state_bytes.h"

namespace acomms::telemetry {
namespace {

constexpr uint64_t kStateVersion = 1;

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
    } else if (held_.size() < kMaxHeld) {
      held_.emplace(message.sequence, Held{message, now});
    }
    return out;
  }
  const int32_t d = sequence_distance(message.sequence, last_);
  if (d == 1) {
    consume(message, now, &out);
  } else if (d > 1) {
    if (held_.size() < kMaxHeld || held_.count(message.sequence)) held_.emplace(message.sequence, Held{message, now});
  } else if (message.kind == MessageKind::kFull && full_time(message, now) > last_time_s_) {
    // A sender that lost its state counts from 0 again: its full is newer
    // than anything we hold, whatever its number says.
    held_.clear();
    consume(message, now, &out);
  } else {
    ++counters_.duplicates;
  }
  release(now, &out);
  return out;
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
      std::optional<uint32_t> skip_to = timed_out_full(now);
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
  // What is now behind us can never be consumed.
  for (auto it = held_.begin(); it != held_.end();) {
    it = sequence_distance(it->first, last_) <= 0 ? held_.erase(it) : std::next(it);
  }
}

std::optional<uint32_t> StreamReceiver::timed_out_full(double now) const {
  std::optional<uint32_t> best;
  int32_t best_distance = 0;
  for (const auto& [sequence, held] : held_) {
    if (held.message.kind != MessageKind::kFull || now - held.arrived < gap_timeout_s_) continue;
    const int32_t d = started_ ? sequence_distance(sequence, last_) : 1;
    if (!best || d < best_distance) {
      best = sequence;
      best_distance = d;
    }
  }
  return best;
}

void StreamReceiver::consume(const WireMessage& message, double now, std::vector<ReceivedPosition>* out) {
  started_ = true;
  last_ = message.sequence;
  if (message.kind == MessageKind::kDelta && !in_step_) {
    ++counters_.out_of_step;
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
    in_step_ = true;
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

void StreamReceiver::undecodable(const WireMessage& message, const char* why) {
  ++counters_.undecodable;
  in_step_ = false;
  decoder_.restore({});
  spdlog::warn("telemetry from {}: message {} does not decode ({}): waiting for the next full", src_,
               message.sequence, why);
}

std::string StreamReceiver::state() const {
  StateWriter out;
  out.put(kStateVersion, 1);
  out.put(started_ ? 1 : 0, 1);
  out.put(in_step_ ? 1 : 0, 1);
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
  uint64_t version = 0, started = 0, in_step = 0, last = 0, offset = 0, last_time = 0, count = 0;
  std::string decoder_state;
  bool ok = in.get(1, &version) && version == kStateVersion && in.get(1, &started) && started <= 1 &&
            in.get(1, &in_step) && in_step <= 1 && in.get(2, &last) && last < kWireSequenceModulus &&
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
    started_ = in_step_ = false;
    last_ = 0;
    day_offset_s_ = last_time_s_ = 0;
    held_.clear();
    return false;
  }
  started_ = started == 1;
  in_step_ = in_step == 1 && decoder_ok;
  last_ = static_cast<uint32_t>(last);
  day_offset_s_ = static_cast<int64_t>(offset);
  last_time_s_ = static_cast<int64_t>(last_time);
  held_ = std::move(held);
  return decoder_ok;
}

}  // namespace acomms::telemetry
