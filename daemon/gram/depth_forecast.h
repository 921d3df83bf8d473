// The forecast strategy of the depth objective, for deep water (Schneider
// (2013) §4.4, the behaviour he calls BHV_MaxSNRDepth; our reading of his
// description, spec §6.4 for the bias).
//
// Problem: in deep water a vehicle changes depth slowly (tens of minutes
// for a kilometre) while the objective's good depths move along range, and
// a convergence zone's caustic has its shadow zone right above it. Chasing
// the best depth of the next window (best_depth.h) keeps the vehicle in
// transit between far-apart maxima, often through a shadow.
// Decision: look at the objective over the windows ahead (a "field", one
// column per window, up to a forecast horizon), and
//   1. if the vehicle is on a ridge (a local maximum over depth, at least
//      its neighbours and above one of them, the nearest to it; it is on it
//      when its own objective is within
//      `ridge_tolerance` of the peak's value) and that
//      ridge can be followed, within the vertical speed, across every column
//      to the horizon, staying high (in each column within `ridge_tolerance`
//      of the best the vehicle could reach by then: "a ridge of high
//      objective", not any bump that fades), it stays on the ridge;
//   2. otherwise it targets the optimum within the horizon that it can
//      reach: among points (column k ≥ 1, depth z) with |z − z₀| ≤ w t_k
//      whose straight path from (0, z₀) does not cross a shadow zone, the
//      best objective B; the target is the EARLIEST point near it (at least
//      (1 − `optimum_tolerance`) B), and in its column the least pitch
//      |z − z₀| / t_k (then the shallowest). Why earliest and not the least
//      pitch over the whole horizon, the thesis's words: re-planned every
//      τ_a, a least-pitch target is nearly always the latest column, so the
//      vehicle creeps toward points it never reaches and cuts across a
//      curved band of good depths (measured on the deep Munk replay,
//      tests/unit/eval/deep_forecast_test.cpp: 0.24 received with least
//      pitch, 0.43 with the earliest, at 0.51 m/s);
//   3. with no such point (nothing ahead receives) it holds its depth.
// "Crossing" a shadow zone: a shadow point on the path after a point that
// is not in shadow (a vehicle that starts in a shadow may leave it). Points
// the limits forbid count as shadow (the path may not touch the bottom).
// The bias towards depth against caustic uncertainty is in the field: its
// steering objective is low-passed from the surface down (spec §6.4) by the
// caller (depth_forecast_field.h); the shadow test uses the raw objective.
// Invariants: the target is an allowed grid depth reachable in its time at
// the vertical speed; the result depends on nothing but the arguments.
// Thread-safe: pure functions.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gram/range_window.h"

namespace acomms::gram {

struct ForecastField {
  std::vector<double> depth_m;  // strictly increasing
  std::vector<double> time_s;   // per column, strictly increasing, time_s[0] = 0 (the window now)
  // [column][depth]: what the vehicle steers by (filtered), and the raw
  // objective that says where the shadow is; allowed: the limits.
  std::vector<std::vector<double>> steer;
  std::vector<std::vector<double>> raw;
  std::vector<std::vector<bool>> allowed;
};

struct ForecastOptions {
  double vertical_speed_mps = 0.75;  // w, > 0
  double ridge_tolerance = 0.05;     // [0, 1]
  // [0, 1], relative to the best B: points of at least (1 − this) B are
  // near-best. 0: the strict optimum. 0.1: the objective's scale is the
  // signal excess over the horizon's best, so 10% of it (about 2 dB of a
  // 20 dB margin) is within the model's error at a caustic.
  double optimum_tolerance = 0.1;
  double shadow_objective = 0.0;     // raw objective at or below: shadow, [0, 1)
};

enum class ForecastChoice { kRidge, kOptimum, kHold };
const char* forecast_choice_name(ForecastChoice choice);  // "ridge", "optimum", "hold"

struct ForecastDecision {
  ForecastChoice choice = ForecastChoice::kHold;
  double target_depth_m = 0;
  double target_time_s = 0;  // 0 with kHold
  double target_objective = 0;
  double vertical_rate_mps = 0;
  // kRidge: the ridge's depth in each column (the path it follows).
  std::vector<double> ridge_depth_m;
  // Where to be `dt` seconds from now: on the straight path to the target
  // (on a ridge: along the ridge's path), then at the target.
  double depth_after(double current_depth_m, double dt) const;
  std::vector<double> ridge_time_s;
};

std::optional<std::string> validate_forecast_field(const ForecastField& field);
std::optional<std::string> validate_forecast_options(const ForecastOptions& options);

// Throws std::invalid_argument (the validators' messages).
ForecastDecision forecast_depth(const ForecastField& field, double current_depth_m, const ForecastOptions& options);

// What a depth-objective query adds to ask for a forecast
// (depth_forecast_field.h builds the field from the model's TL).
struct DepthForecastRequest {
  double forecast_horizon_s = 3600;  // ≥ the query's horizon_s (τ_a): one column every τ_a
  double current_depth_m = 0;        // ≥ 0
  // How well a caustic's depth is known, m (the thesis: about 50); the
  // steering objective is low-passed from the surface with cutoff 1/this
  // (spec §6.4). 0: the query's own low-pass, if any.
  double caustic_uncertainty_m = 50;
  ForecastOptions options;  // vertical speed and tolerances
  // Where the vehicle's straight leg ends (a turn, the end of its run), m:
  // the windows beyond it are not where the vehicle will be, so the
  // forecast stops there (the next window is kept). Unset: no end.
  std::optional<double> leg_end_range_m;
};

struct DepthForecastResult {
  ForecastField field;
  std::vector<RangeWindow> windows;  // per column
  double horizon_used_s = 0;         // the last column's time (the grid may end first)
  ForecastDecision decision;
  double next_depth_m = 0;  // decision.depth_after(current depth, τ_a): where to be at the next window
};

// Each column is a depth objective over a window: a query may ask at most
// this many (120: an hour at τ_a = 30 s, four at 120 s), so that one request
// cannot occupy the model service for minutes.
inline constexpr double kMaxForecastColumns = 120;

std::optional<std::string> validate_depth_forecast_request(const DepthForecastRequest& request, double horizon_s);

}  // namespace acomms::gram
