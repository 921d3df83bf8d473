// libFuzzer target: received telemetry into a stream's receiver state
// (telemetry/wire_message.h, telemetry/stream_receiver.h). What the link
// hands over is noise- or attacker-controlled: any DCCL frame that decodes
// as PositionFull/PositionDelta, in any order, repeated or not. Receiving
// must never crash, and the receiver's state must survive the store
// (state() restores to the same state()).
//
// Two ways in, chosen by the first byte's top bit:
//   raw       the rest is frames ([length byte][bytes]) decoded with the
//             shipped DCCL types, every message fed to the receiver;
//   stream    a real sender's messages over a straight-then-turning track,
//             then the input's bytes drop, repeat, reorder and flip bits of
//             them: deep in the decoder, where raw bytes rarely get.
// The low bits of the first byte pick the observer and model.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "dccl/codec.h"
#include "telemetry/stream_receiver.h"
#include "telemetry/stream_sender.h"

namespace {

using namespace acomms::telemetry;

constexpr double kNow = 1764000000;

void check_state(const TelemetryConfig& config, const StreamReceiver& receiver) {
  StreamReceiver copy(config, 2, 600);
  const std::string state = receiver.state();
  // A state the receiver wrote restores, to the same state: the decoder
  // only ever accepts innovations inside the bounds, so its history replays.
  if (!copy.restore(state) || copy.state() != state) std::abort();
}

std::vector<WireMessage> real_stream(const TelemetryConfig& config) {
  StreamSender sender(config, 2, 1);
  std::vector<WireMessage> out;
  for (int n = 0; n < 80; ++n) {
    Sample sample;
    sample.time_s = static_cast<int64_t>(kNow) + n * static_cast<int64_t>(config.tau_s);
    const double s = n * 10.0;
    sample.position_m = {n < 40 ? 1.5 * s : 600 - 0.4 * (s - 400), n < 40 ? 3.0 : 1.4 * (s - 400),
                         -20.0 - 10.0 * ((n / 7) % 2)};
    if (n == 55) sample.position_m[0] += 100;  // a GPS jump
    out.push_back(sender.send(sample));
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static acomms::dccl::Codec* codec = [] {
    auto* c = new acomms::dccl::Codec();
    c->load("acomms/telemetry/messages.proto", {ACOMMS_PROTO_DIR});
    return c;
  }();
  if (size == 0) return 0;
  TelemetryConfig config;
  config.observer = (data[0] & 1) ? ObserverKind::kKalman : ObserverKind::kFixedSpeed;
  config.model = static_cast<ModelKind>((data[0] >> 1) & 3);
  config.full_every = 30;
  StreamReceiver receiver(config, 2, 600);
  double now = kNow;
  size_t i = 1;
  if ((data[0] & 0x80) == 0) {
    while (i < size) {
      const size_t n = std::min<size_t>(data[i], size - i - 1);
      std::string_view frame(reinterpret_cast<const char*>(data + i + 1), n);
      i += n + 1;
      std::vector<std::unique_ptr<google::protobuf::Message>> messages;
      try {
        messages = codec->decode(frame);
      } catch (const acomms::dccl::Error&) {
        continue;
      }
      for (const auto& message : messages) {
        WireMessage wire;
        try {
          wire = from_dccl(*message);
        } catch (const std::invalid_argument&) {
          continue;
        }
        now += 7;
        receiver.receive(wire, now);
        check_state(config, receiver);
      }
    }
    return 0;
  }
  static const std::vector<WireMessage> streams[8] = {
      real_stream({.observer = ObserverKind::kFixedSpeed, .model = ModelKind::kUniform, .full_every = 30}),
      real_stream({.observer = ObserverKind::kKalman, .model = ModelKind::kUniform, .full_every = 30}),
      real_stream({.observer = ObserverKind::kFixedSpeed, .model = ModelKind::kGaussian, .full_every = 30}),
      real_stream({.observer = ObserverKind::kKalman, .model = ModelKind::kGaussian, .full_every = 30}),
      real_stream({.observer = ObserverKind::kFixedSpeed, .model = ModelKind::kAdaptive, .full_every = 30}),
      real_stream({.observer = ObserverKind::kKalman, .model = ModelKind::kAdaptive, .full_every = 30}),
      real_stream({.observer = ObserverKind::kFixedSpeed, .model = ModelKind::kLearned, .full_every = 30}),
      real_stream({.observer = ObserverKind::kKalman, .model = ModelKind::kLearned, .full_every = 30}),
  };
  const std::vector<WireMessage>& stream = streams[data[0] & 7];
  // Each pair of bytes: which message (mod the stream) and what to do to it.
  for (; i + 1 < size; i += 2) {
    WireMessage message = stream[data[i] % stream.size()];
    const uint8_t action = data[i + 1];
    if ((action & 0xc0) == 0xc0 && !message.body.empty()) {
      message.body[action % message.body.size()] = !message.body[action % message.body.size()];
    } else if ((action & 0xc0) == 0x80) {
      message.body.resize(message.body.size() / 2);
    } else if ((action & 0xc0) == 0x40) {
      message.sequence = (message.sequence + action) % kWireSequenceModulus;
    }
    now += action & 0x3f;
    receiver.receive(message, now);
    check_state(config, receiver);
  }
  return 0;
}
