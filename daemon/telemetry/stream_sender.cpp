#include "telemetry/stream_sender.h"

#include "telemetry/state_bytes.h"

namespace acomms::telemetry {
namespace {
constexpr uint64_t kStateVersion = 2;  // 2: last_fresh
}

StreamSender::StreamSender(const TelemetryConfig& config, int32_t src, int32_t dest)
    : encoder_(config), src_(src), dest_(dest) {}

WireMessage StreamSender::send(const Sample& sample) {
  EncodedMessage encoded = encoder_.encode(sample);
  if (encoded.kind == MessageKind::kDelta && encoded.body_bits > kMaxDeltaBodyBits) {
    // Never with the shipped models (a codeword is at most 3 x 30 + 2
    // bits); a full is always possible. Fresh: the statistics learned the
    // delta that is not sent.
    encoder_.request_fresh();
    encoded = encoder_.encode(sample);
  }
  sequence_ = (sequence_ + 1) % kWireSequenceModulus;
  if (encoded.fresh) last_fresh_ = sequence_;
  WireMessage message;
  message.kind = encoded.kind;
  message.src = src_;
  message.dest = dest_;
  message.sequence = sequence_;
  message.body = body_of(encoded);
  return message;
}

void StreamSender::continue_after(uint32_t sequence) {
  if (sequence_distance(sequence, sequence_) > 0) {
    sequence_ = sequence % kWireSequenceModulus;
    // The encoder's state does not include that message, which the
    // receiver's statistics will.
    encoder_.request_fresh();
  }
}

bool StreamSender::on_feedback(std::optional<uint32_t> heard) {
  if (heard && last_fresh_ && sequence_distance(*last_fresh_, *heard) > 0) return false;
  encoder_.request_fresh();
  return true;
}

std::string StreamSender::state() const {
  StateWriter out;
  out.put(kStateVersion, 1);
  out.put(sequence_, 2);
  out.put(last_fresh_ ? *last_fresh_ : kWireSequenceModulus, 2);
  out.put_bytes(encoder_.state());
  return out.take();
}

bool StreamSender::restore(std::string_view state) {
  StateReader in(state);
  uint64_t version = 0, sequence = 0, fresh = 0;
  std::string encoder_state;
  if (in.get(1, &version) && version == kStateVersion && in.get(2, &sequence) &&
      sequence < kWireSequenceModulus && in.get(2, &fresh) && fresh <= kWireSequenceModulus &&
      in.get_bytes(&encoder_state) && in.done() && encoder_.restore(encoder_state)) {
    sequence_ = static_cast<uint32_t>(sequence);
    last_fresh_.reset();
    if (fresh < kWireSequenceModulus) last_fresh_ = static_cast<uint32_t>(fresh);
    return true;
  }
  encoder_.restore({});  // starts over: the next message is a fresh full
  sequence_ = kWireSequenceModulus - 1;
  last_fresh_.reset();
  return false;
}

}  // namespace acomms::telemetry
