// Position telemetry: encode and decode time per position, for each observer
// (with the Gaussian model, whose tables follow the observer's variance, and
// with our learned model, which rebuilds a table per axis per sample).
// Goal: < 20 us per position with the Kalman filter. Also the whole link
// round trip per position (sender, DCCL both ways, receiver).
//
// The track is a generated AUV lawnmower (daemon/eval/track_generator.h),
// sampled every 10 s; a pass over it includes its full transmissions.

#include <benchmark/benchmark.h>

#include <vector>

#include "eval/track_generator.h"
#include "telemetry/telemetry_decoder.h"
#include "telemetry/telemetry_encoder.h"
#include "dccl/codec.h"
#include "telemetry/stream_receiver.h"
#include "telemetry/stream_sender.h"

namespace {

using namespace acomms::telemetry;

const std::vector<Sample>& track() {
  static const std::vector<Sample> samples =
      sample_track(acomms::eval::generate_track(acomms::eval::TrackKind::kAuv, 1, 4 * 3600), 10);
  return samples;
}

TelemetryConfig config_of(const benchmark::State& state) {
  TelemetryConfig config;
  config.observer = static_cast<ObserverKind>(state.range(0));
  config.model = static_cast<ModelKind>(state.range(1));
  return config;
}

void label(benchmark::State& state) {
  const TelemetryConfig config = config_of(state);
  state.SetLabel(std::string(name_of(config.observer)) + " + " + std::string(name_of(config.model)));
}

void BM_EncodePerPosition(benchmark::State& state) {
  const TelemetryConfig config = config_of(state);
  const std::vector<Sample>& samples = track();
  auto encoder = std::make_unique<TelemetryEncoder>(config);
  size_t i = 0;
  for (auto _ : state) {
    if (i == samples.size()) {
      state.PauseTiming();
      encoder = std::make_unique<TelemetryEncoder>(config);
      i = 0;
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(encoder->encode(samples[i++]));
  }
  label(state);
}

void BM_DecodePerPosition(benchmark::State& state) {
  const TelemetryConfig config = config_of(state);
  std::vector<std::string> messages;
  TelemetryEncoder encoder(config);
  for (const Sample& sample : track()) messages.push_back(encoder.encode(sample).bytes);
  auto decoder = std::make_unique<TelemetryDecoder>(config);
  size_t i = 0;
  for (auto _ : state) {
    if (i == messages.size()) {
      state.PauseTiming();
      decoder = std::make_unique<TelemetryDecoder>(config);
      i = 0;
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(decoder->decode(messages[i++]));
  }
  label(state);
}

// What the daemon does per position on top: the wire sequence, the DCCL
// message both ways (PositionDelta/PositionFull), and the receiver's order
// checks; the store writes are the group-commit writer's (journal_bench).
void BM_LinkRoundTripPerPosition(benchmark::State& state) {
  const TelemetryConfig config = config_of(state);
  static const acomms::dccl::Codec* codec = [] {
    auto* c = new acomms::dccl::Codec();
    c->load("acomms/telemetry/messages.proto");
    return c;
  }();
  const std::vector<Sample>& samples = track();
  auto sender = std::make_unique<StreamSender>(config, 2, 1);
  auto receiver = std::make_unique<StreamReceiver>(config, 2, 1800);
  size_t i = 0;
  for (auto _ : state) {
    if (i == samples.size()) {
      state.PauseTiming();
      sender = std::make_unique<StreamSender>(config, 2, 1);
      receiver = std::make_unique<StreamReceiver>(config, 2, 1800);
      i = 0;
      state.ResumeTiming();
    }
    const Sample& sample = samples[i++];
    const std::string bytes = codec->encode(*to_dccl(*codec, sender->send(sample)));
    WireMessage back = from_dccl(*codec->decode(bytes).at(0));
    benchmark::DoNotOptimize(receiver->receive(back, static_cast<double>(sample.time_s)));
  }
  label(state);
}

void observers_and_models(benchmark::internal::Benchmark* b) {
  for (ObserverKind observer : {ObserverKind::kFixedSpeed, ObserverKind::kKalman})
    for (ModelKind model : {ModelKind::kGaussian, ModelKind::kAdaptive, ModelKind::kLearned})
      b->Args({static_cast<int64_t>(observer), static_cast<int64_t>(model)});
}

BENCHMARK(BM_EncodePerPosition)->Apply(observers_and_models)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DecodePerPosition)->Apply(observers_and_models)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LinkRoundTripPerPosition)
    ->Args({static_cast<int64_t>(ObserverKind::kFixedSpeed), static_cast<int64_t>(ModelKind::kLearned)})
    ->Args({static_cast<int64_t>(ObserverKind::kKalman), static_cast<int64_t>(ModelKind::kLearned)})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
