// Lossless round trips: every observer x model on generated tracks (AUV
// lawnmower with yo-yo, glider sawtooth, surfacing gaps, GPS jumps), each
// message decoded by a separate decoder to exactly the sender's grid
// position and time; and our learned model beating the thesis's models.

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "eval/realistic_track.h"
#include "eval/track_generator.h"
#include "telemetry/telemetry_decoder.h"
#include "telemetry/telemetry_encoder.h"

namespace acomms::telemetry {
namespace {

struct Cost {
  double mean_delta_bits = 0;
  int deltas = 0, fulls = 0;
};

Cost round_trip(const std::vector<Sample>& samples, const TelemetryConfig& config) {
  TelemetryEncoder encoder(config);
  TelemetryDecoder decoder(config);
  Cost cost;
  double sum = 0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const EncodedMessage message = encoder.encode(samples[i]);
    const DecodedMessage decoded = decoder.decode(message.bytes);
    EXPECT_EQ(decoded.outcome, DecodeOutcome::kPosition) << i;
    EXPECT_EQ(decoded.kind, message.kind) << i;
    EXPECT_EQ(unwrap_time_of_day(decoded.time_s, samples[i].time_s), samples[i].time_s) << i;
    for (int axis = 0; axis < kAxes; ++axis) {
      const int64_t want = std::llround(samples[i].position_m[axis] / config.precision_m);
      EXPECT_EQ(decoded.grid[axis], want) << "sample " << i << " axis " << axis;
    }
    if (::testing::Test::HasFailure()) return cost;
    if (message.kind == MessageKind::kDelta) {
      ++cost.deltas;
      sum += static_cast<double>(message.body_bits);
    } else {
      ++cost.fulls;
    }
  }
  cost.mean_delta_bits = cost.deltas > 0 ? sum / cost.deltas : 0;
  return cost;
}

std::vector<Sample> auv_samples() {
  return sample_track(eval::generate_track(eval::TrackKind::kAuv, 7, 2 * 3600 + 900), 10);
}

TEST(RoundTrip, EveryObserverAndModelOnAnAuvLawnmowerWithYoYoAndSurfacing) {
  const std::vector<Sample> samples = auv_samples();
  ASSERT_GT(samples.size(), 700u);
  for (ObserverKind observer : {ObserverKind::kFixedSpeed, ObserverKind::kKalman}) {
    for (ModelKind model : {ModelKind::kUniform, ModelKind::kGaussian, ModelKind::kAdaptive, ModelKind::kLearned}) {
      TelemetryConfig config;
      config.observer = observer;
      config.model = model;
      const Cost cost = round_trip(samples, config);
      ASSERT_FALSE(HasFailure()) << name_of(observer) << " + " << name_of(model);
      // two surfacings (new segments) and a full every 60 deltas at least
      EXPECT_GE(cost.fulls, 3 + static_cast<int>(samples.size() / 61) - 1);
      if (model == ModelKind::kUniform) {
        EXPECT_GE(cost.mean_delta_bits, 19.97);
        EXPECT_LE(cost.mean_delta_bits, 19.97 + 1.5);
      }
    }
  }
}

TEST(RoundTrip, GliderSawtoothWithCurrentsAtHalfMetrePrecision) {
  const std::vector<Sample> samples =
      sample_track(eval::generate_track(eval::TrackKind::kGlider, 3, 3 * 3600), 10);
  for (ObserverKind observer : {ObserverKind::kFixedSpeed, ObserverKind::kKalman}) {
    for (ModelKind model : {ModelKind::kGaussian, ModelKind::kAdaptive, ModelKind::kLearned}) {
      TelemetryConfig config;
      config.observer = observer;
      config.model = model;
      config.speed_mps = 0.3;
      config.precision_m = 0.5;
      round_trip(samples, config);
      ASSERT_FALSE(HasFailure()) << name_of(observer) << " + " << name_of(model);
    }
  }
}

// The realistic tracks (eval/realistic_track.h): GPS jumps inside a
// segment, currents, irregular turns, depth overshoot; a 1 Hz and a 4 s log.
TEST(RoundTrip, EveryObserverAndModelOnRealisticTorpedoAuvAndGliderTracks) {
  struct Track {
    eval::TrackKind kind;
    double speed_mps, duration_s;
  };
  for (const Track& track : {Track{eval::TrackKind::kAuv, 1.5, 2.5 * 3600}, Track{eval::TrackKind::kGlider, 0.3, 5 * 3600}}) {
    const std::vector<Sample> samples = sample_track(eval::generate_realistic_track(track.kind, 11, track.duration_s), 10);
    ASSERT_GT(samples.size(), 850u);
    for (ObserverKind observer : {ObserverKind::kFixedSpeed, ObserverKind::kKalman}) {
      for (ModelKind model : {ModelKind::kUniform, ModelKind::kGaussian, ModelKind::kAdaptive, ModelKind::kLearned}) {
        TelemetryConfig config;
        config.observer = observer;
        config.model = model;
        config.speed_mps = track.speed_mps;
        const Cost cost = round_trip(samples, config);
        ASSERT_FALSE(HasFailure()) << name_of(observer) << " + " << name_of(model);
        EXPECT_GT(cost.deltas, static_cast<int>(samples.size() * 9 / 10)) << name_of(observer) << " + " << name_of(model);
      }
    }
  }
}

TEST(RoundTrip, AGpsJumpOfAHundredMetresWithinASegmentGoesAsAFull) {
  std::vector<Fix> fixes;
  for (int t = 0; t <= 600; t += 2) {
    const double jump = t >= 300 ? 100 : 0;  // navigation reset by a GPS fix
    fixes.push_back({static_cast<double>(t), {1.5 * t + jump, 0.2 * t - jump, -10 - 0.3 * (t % 100)}});
  }
  const std::vector<Sample> samples = sample_track(fixes, 10);
  for (ObserverKind observer : {ObserverKind::kFixedSpeed, ObserverKind::kKalman}) {
    TelemetryConfig config;
    config.observer = observer;
    TelemetryEncoder encoder(config);
    TelemetryDecoder decoder(config);
    for (const Sample& sample : samples) {
      const EncodedMessage message = encoder.encode(sample);
      EXPECT_EQ(message.kind == MessageKind::kFull, sample.time_s == 0 || sample.time_s == 300) << sample.time_s;
      EXPECT_EQ(decoder.decode(message.bytes).grid, message.position);
    }
  }
}

TEST(RoundTrip, AFullEveryNDeltas) {
  std::vector<Fix> fixes;
  for (int t = 0; t <= 1000; t += 10) fixes.push_back({static_cast<double>(t), {1.0 * t, 0, -5}});
  TelemetryConfig config;
  config.full_every = 7;
  TelemetryEncoder encoder(config);
  int index = 0;
  for (const Sample& sample : sample_track(fixes, 10)) {
    EXPECT_EQ(encoder.encode(sample).kind == MessageKind::kFull, index % 8 == 0) << index;
    ++index;
  }
}

TEST(RoundTrip, LearnedModelBeatsTheThesisModelsOnAnAuvTrack) {
  const std::vector<Sample> samples = auv_samples();
  for (ObserverKind observer : {ObserverKind::kFixedSpeed, ObserverKind::kKalman}) {
    std::map<ModelKind, double> bits;
    for (ModelKind model : {ModelKind::kUniform, ModelKind::kGaussian, ModelKind::kAdaptive, ModelKind::kLearned}) {
      TelemetryConfig config;
      config.observer = observer;
      config.model = model;
      bits[model] = round_trip(samples, config).mean_delta_bits;
    }
    // 0.5, not 2 bits, since the statistics outlive fulls: the adaptive
    // counts no longer restart uniform every 61 samples (on this track
    // 13.4 -> 8.7 bits with fixed speed, 15.5 -> 10.9 with Kalman; learned
    // 8.3 -> 7.5 and 11.3 -> 10.0).
    EXPECT_LT(bits[ModelKind::kLearned], bits[ModelKind::kAdaptive] - 0.5) << name_of(observer);
    EXPECT_LT(bits[ModelKind::kLearned], bits[ModelKind::kGaussian] - 2) << name_of(observer);
    EXPECT_LT(bits[ModelKind::kAdaptive], bits[ModelKind::kUniform]) << name_of(observer);
  }
}

}  // namespace
}  // namespace acomms::telemetry
