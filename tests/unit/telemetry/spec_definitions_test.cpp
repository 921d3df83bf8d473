// The thesis's models as the spec defines them (shared/spec/telemetry.md
// sections 1-3), written again here from the spec's text alone, against
// ours on a realistic torpedo AUV track (eval/realistic_track.h): issue 28
// found our fixed speed + adaptive 2-5 bits above an independent
// implementation of the spec on real tracks. The cause was the statistics
// restarting at every full (fixed: they carry across fulls); this checks
// the rest of the definitions: quantisation (y = round(p / precision)),
// the fixed-speed prediction, the innovation (an integer in [-50, 51), a
// full outside it), and the adaptive model ((N_d + 1) / (m + 101), counts
// from 0, one per innovation sent, never restarted). Same innovations
// delta by delta, and codewords within the coder's end cost of the
// reference's information.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "eval/realistic_track.h"
#include "telemetry/sampler.h"
#include "telemetry/telemetry_encoder.h"

namespace acomms::telemetry {
namespace {

// The spec's fixed-speed observer and adaptive model, per axis, in doubles.
class SpecFixedSpeedAdaptive {
 public:
  SpecFixedSpeedAdaptive(double speed_mps, double tau_s) : step_(speed_mps * tau_s), counts_(3, std::vector<int>(101)) {}
  void full(const std::array<int64_t, 3>& y) { history_ = {y}; }
  // The innovation of y against the prediction; false when out of range.
  bool innovation(const std::array<int64_t, 3>& y, std::array<int64_t, 3>* dy) const {
    std::array<double, 3> predicted;
    const auto& last = history_.back();
    for (int a = 0; a < 3; ++a) predicted[a] = static_cast<double>(last[a]);
    if (history_.size() >= 2) {
      const auto& before = history_[history_.size() - 2];
      const double heading = std::atan2(static_cast<double>(last[1] - before[1]), static_cast<double>(last[0] - before[0]));
      predicted[0] += step_ * std::cos(heading);
      predicted[1] += step_ * std::sin(heading);
      predicted[2] += static_cast<double>(last[2] - before[2]);
    }
    bool in_range = true;
    for (int a = 0; a < 3; ++a) {
      (*dy)[a] = static_cast<int64_t>(std::llround(static_cast<double>(y[a]) - predicted[a]));
      in_range = in_range && (*dy)[a] >= -50 && (*dy)[a] < 51;
    }
    return in_range;
  }
  // -log2 p of dy under the adaptive model, then counts it.
  double information_then_count(const std::array<int64_t, 3>& dy) {
    double bits = 0;
    for (int a = 0; a < 3; ++a) {
      int m = 0;
      for (int n : counts_[a]) m += n;
      bits -= std::log2(static_cast<double>(counts_[a][dy[a] + 50] + 1) / (m + 101));
      ++counts_[a][dy[a] + 50];
    }
    return bits;
  }
  void accept(const std::array<int64_t, 3>& y) {
    history_.push_back(y);
    if (history_.size() > 2) history_.erase(history_.begin());
  }
  bool standing() const {
    return history_.size() >= 2 && history_[0][0] == history_[1][0] && history_[0][1] == history_[1][1];
  }

 private:
  double step_;
  std::vector<std::array<int64_t, 3>> history_;
  std::vector<std::vector<int>> counts_;
};

TEST(SpecDefinitions, FixedSpeedAdaptiveIsTheSpecsOnARealisticTorpedoAuvTrack) {
  TelemetryConfig config;
  config.observer = ObserverKind::kFixedSpeed;
  config.model = ModelKind::kAdaptive;
  config.full_every = 10000;  // fulls only where the spec sends them
  TelemetryEncoder encoder(config);
  SpecFixedSpeedAdaptive spec(config.speed_mps, config.tau_s);
  double ours = 0, reference = 0;
  int deltas = 0, fulls = 0, standing = 0;
  for (const Sample& sample :
       sample_track(eval::generate_realistic_track(eval::TrackKind::kAuv, 1, 2.2 * 3600), config.tau_s)) {
    std::array<int64_t, 3> y;
    for (int a = 0; a < 3; ++a) y[a] = std::llround(sample.position_m[a] / config.precision_m);
    const EncodedMessage message = encoder.encode(sample);
    ASSERT_EQ(message.position, y) << sample.time_s;  // quantisation
    std::array<int64_t, 3> dy{};
    const bool first = fulls == 0;
    const bool in_range = !first && spec.innovation(y, &dy);
    if (!first && spec.standing()) {
      // The spec's atan2(0, 0) = 0 predicts a move east; ours predicts the
      // last position (fixed_speed_observer.h). Not compared.
      ++standing;
      if (message.kind == MessageKind::kFull) {
        spec.full(y);
        ++fulls;
      } else {
        spec.information_then_count({message.innovation[0], message.innovation[1], message.innovation[2]});
        spec.accept(y);
      }
      continue;
    }
    ASSERT_EQ(message.kind == MessageKind::kFull, !in_range) << sample.time_s;
    if (message.kind == MessageKind::kFull) {
      spec.full(y);
      ++fulls;
      continue;
    }
    for (int a = 0; a < 3; ++a) ASSERT_EQ(message.innovation[a], dy[a]) << sample.time_s << " axis " << a;
    ours += static_cast<double>(message.body_bits);
    reference += spec.information_then_count(dy);
    spec.accept(y);
    ++deltas;
  }
  ASSERT_GT(deltas, 700);
  EXPECT_LT(standing, deltas / 100);
  // An arithmetic codeword with the exact end costs its information plus
  // at most about two bits (spec section 4); on average about one.
  const double ours_mean = ours / deltas, reference_mean = reference / deltas;
  EXPECT_GE(ours_mean, reference_mean) << ours_mean << " vs " << reference_mean;
  EXPECT_LE(ours_mean, reference_mean + 1.5) << ours_mean << " vs " << reference_mean;
  std::printf("fixed speed + adaptive: ours %.2f bits per delta, the spec's information %.2f\n", ours_mean,
              reference_mean);
}

}  // namespace
}  // namespace acomms::telemetry
