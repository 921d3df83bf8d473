#pragma once
// The parameters both ends of a telemetry stream must agree on.
//
// Position telemetry (shared/spec/telemetry.md) only works when sender and
// receiver run the same observer and probability model with the same
// parameters: each end predicts the next sample and the innovation is coded
// against that prediction. A TelemetryConfig is that agreement; its
// fingerprint() is stored with the stream state so that a restart under a
// different config starts over with a full transmission instead of decoding
// garbage. Defaults are the thesis's (tau 10 s, 1 m, [-50, 51), sigma_j^2
// 1e-3, R = 25 I).
//
// Thread-safe: a plain value and pure functions.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace acomms::telemetry {

enum class ObserverKind { kFixedSpeed, kKalman };
enum class ModelKind { kUniform, kGaussian, kAdaptive, kLearned };

// "fixed_speed", "kalman" / "uniform", "gaussian", "adaptive", "learned".
std::string_view name_of(ObserverKind kind);
std::string_view name_of(ModelKind kind);
std::optional<ObserverKind> observer_kind_of(std::string_view name);
std::optional<ModelKind> model_kind_of(std::string_view name);

// Axes: x east, y north, z up (negative down), metres from the agreed datum.
inline constexpr int kAxes = 3;

struct TelemetryConfig {
  ObserverKind observer = ObserverKind::kKalman;
  ModelKind model = ModelKind::kLearned;
  // Sampling period, whole seconds: sample times are multiples of tau, and a
  // full transmission codes its time to the second.
  uint32_t tau_s = 10;
  double precision_m = 1;
  // Innovations dy in [innovation_min, innovation_max), units of precision.
  int32_t innovation_min = -50;
  int32_t innovation_max = 51;
  // Fixed-speed observer (and its Gaussian model's sigma = speed * tau).
  double speed_mps = 1.5;
  // Kalman observer: jerk variance sigma_j^2 and measurement noise R (m^2).
  double sigma_j2 = 1e-3;
  double r_m2 = 25;
  // A full transmission after this many deltas, so a receiver that joined
  // late or lost its state is back in step within N + 1 samples.
  uint32_t full_every = 60;
  // The operating region a full transmission codes (uniformly, to precision).
  std::array<double, kAxes> region_min_m = {-50000, -50000, -6000};
  std::array<double, kAxes> region_max_m = {50000, 50000, 100};
};

// Throws std::invalid_argument naming the field and the bound it broke.
void validate(const TelemetryConfig& config);

// A hash of every field that changes what is sent (FNV-1a over the fields'
// in-memory bytes, so for state kept on the machine that wrote it, never for
// the wire): equal configs have equal fingerprints.
uint64_t fingerprint(const TelemetryConfig& config);

}  // namespace acomms::telemetry
