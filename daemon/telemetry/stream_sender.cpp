#include "telemetry/stream_sender.h"

#include "telemetry/state_bytes.h"

namespace acomms::telemetry {
namespace {
constexpr uint64_t kStateVersion = 1;
}

StreamSender::StreamSender(const TelemetryConfig& config, int32_t src, int32_t dest)
    : encoder_(config), src_(src), dest_(dest) {}

WireMessage StreamSender::send(const Sample& sample) {
  EncodedMessage encoded = encoder_.encode(sample);
  if (encoded.kind == MessageKind::kDelta && encoded.body_bits > kMaxDeltaBodyBits) {
    // Never with the shipped models (a codeword is at most 3 x 30 + 2
    // bits); a full is always possible.
    encoder_.request_full();
    encoded = encoder_.encode(sample);
  }
  sequence_ = (sequence_ + 1) % kWireSequenceModulus;
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
    // The encoder's state does not include that message.
    encoder_.request_full();
  }
}

std::string StreamSender::state() const {
  StateWriter out;
  out.put(kStateVersion, 1);
  out.put(sequence_, 2);
  out.put_bytes(encoder_.state());
  return out.take();
}

bool StreamSender::restore(std::string_view state) {
  StateReader in(state);
  uint64_t version = 0, sequence = 0;
  std::string encoder_state;
  if (in.get(1, &version) && version == kStateVersion && in.get(2, &sequence) &&
      sequence < kWireSequenceModulus && in.get_bytes(&encoder_state) && in.done() &&
      encoder_.restore(encoder_state)) {
    sequence_ = static_cast<uint32_t>(sequence);
    return true;
  }
  encoder_.restore({});  // starts over: the next message is a full
  sequence_ = kWireSequenceModulus - 1;
  return false;
}

}  // namespace acomms::telemetry
