// The best depth within the vehicle's limits.
//
// Problem: the objective's maximum may lie where the vehicle must not go
// (above its minimum depth, below its rating, or too close to the bottom
// that rises under the window). Decision: a grid depth d is allowed when
//     min_depth_m ≤ d ≤ max_depth_m  and  d ≤ bottom_m − min_altitude_m,
// with bottom_m the SHALLOWEST bottom under the range window (the vehicle
// crosses the whole window, so the altitude must hold over all of it).
// Among allowed depths the highest objective wins; ties (equal within
// kObjectiveTie) go to the SHALLOWEST depth — deterministic, and the depth
// of least pressure and least risk from the bottom. If the objective is 0 at
// every allowed depth (no depth is predicted to receive), the result is the
// shallowest allowed depth with `any_signal = false`, so a caller can keep
// its current plan rather than dive on a score of zero.
// Thread-safe: pure functions.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>

#include "acomms/gram/environment.pb.h"
#include "gram/range_window.h"

namespace acomms::gram {

struct VehicleLimits {
  double min_depth_m = 0;     // ≥ 0
  double max_depth_m = 0;     // ≥ min_depth_m
  double min_altitude_m = 0;  // ≥ 0, clearance above the bottom
};

struct BestDepth {
  std::size_t index = 0;  // into the depth grid
  double depth_m = 0;
  double objective = 0;
  bool any_signal = false;       // objective > 0 somewhere allowed
  double deepest_allowed_m = 0;  // min(max_depth_m, bottom_m − min_altitude_m)
};

inline constexpr double kObjectiveTie = 1e-12;

std::optional<std::string> validate_limits(const VehicleLimits& limits);

// Bottom depth at range r: the bathymetry, linear between points and
// extended level beyond them; the last SSP depth if there is none.
double bottom_depth_at(const Environment& env, double range_m);
// The shallowest bottom over [window.begin_m, window.end_m].
double shallowest_bottom(const Environment& env, const RangeWindow& window);

// Throws std::invalid_argument on bad limits, mismatched sizes, or when no
// grid depth is allowed (the message gives the allowed interval and grid).
BestDepth best_depth(std::span<const double> depth_m, std::span<const double> objective,
                     const VehicleLimits& limits, double bottom_m);

}  // namespace acomms::gram
