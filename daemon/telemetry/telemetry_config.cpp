#include "telemetry/telemetry_config.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace acomms::telemetry {
namespace {

constexpr std::array<std::string_view, 2> kObserverNames = {"fixed_speed", "kalman"};
constexpr std::array<std::string_view, 4> kModelNames = {"uniform", "gaussian", "adaptive", "learned"};

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("telemetry config: " + what);
}

}  // namespace

std::string_view name_of(ObserverKind kind) { return kObserverNames[static_cast<size_t>(kind)]; }
std::string_view name_of(ModelKind kind) { return kModelNames[static_cast<size_t>(kind)]; }

std::optional<ObserverKind> observer_kind_of(std::string_view name) {
  for (size_t i = 0; i < kObserverNames.size(); ++i)
    if (kObserverNames[i] == name) return static_cast<ObserverKind>(i);
  return std::nullopt;
}

std::optional<ModelKind> model_kind_of(std::string_view name) {
  for (size_t i = 0; i < kModelNames.size(); ++i)
    if (kModelNames[i] == name) return static_cast<ModelKind>(i);
  return std::nullopt;
}

void validate(const TelemetryConfig& c) {
  require(c.tau_s >= 1 && c.tau_s <= 3600, "tau_s must be within [1, 3600] s");
  require(std::isfinite(c.precision_m) && c.precision_m >= 0.01 && c.precision_m <= 1000,
          "precision_m must be within [0.01, 1000] m");
  require(c.innovation_min < 0 && c.innovation_max > 0,
          "the innovation bounds [innovation_min, innovation_max) must hold 0");
  require(int64_t{c.innovation_max} - c.innovation_min <= 4096,
          "the innovation bounds may hold at most 4096 values");
  require(std::isfinite(c.speed_mps) && c.speed_mps > 0 && c.speed_mps <= 100,
          "speed_mps must be within (0, 100] m/s");
  require(std::isfinite(c.sigma_j2) && c.sigma_j2 > 0 && c.sigma_j2 <= 1e6,
          "sigma_j2 must be within (0, 1e6]");
  require(std::isfinite(c.r_m2) && c.r_m2 > 0 && c.r_m2 <= 1e8, "r_m2 must be within (0, 1e8] m^2");
  require(c.full_every >= 1 && c.full_every <= 10000, "full_every must be within [1, 10000]");
  for (int axis = 0; axis < kAxes; ++axis) {
    const double lo = c.region_min_m[axis], hi = c.region_max_m[axis];
    require(std::isfinite(lo) && std::isfinite(hi) && lo < hi,
            "region axis " + std::to_string(axis) + ": region_min_m must be below region_max_m");
    require((hi - lo) / c.precision_m < 4.0e9,
            "region axis " + std::to_string(axis) + " spans more than 2^32 precision steps");
  }
}

uint64_t fingerprint(const TelemetryConfig& c) {
  uint64_t hash = 1469598103934665603ull;
  auto mix = [&hash](const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
  };
  auto mix_value = [&mix](auto value) { mix(&value, sizeof value); };
  mix_value(static_cast<int32_t>(c.observer));
  mix_value(static_cast<int32_t>(c.model));
  mix_value(c.tau_s);
  mix_value(c.precision_m);
  mix_value(c.innovation_min);
  mix_value(c.innovation_max);
  mix_value(c.speed_mps);
  mix_value(c.sigma_j2);
  mix_value(c.r_m2);
  mix_value(c.full_every);
  for (int axis = 0; axis < kAxes; ++axis) {
    mix_value(c.region_min_m[axis]);
    mix_value(c.region_max_m[axis]);
  }
  return hash;
}

}  // namespace acomms::telemetry
