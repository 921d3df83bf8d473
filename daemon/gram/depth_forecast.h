// The forecast strategy of the depth objective, for deep water (Schneider
// (2013) §4.4, the behaviour he calls BHV_MaxSNRDepth; our reading of his
// description, generalised to a path planner; spec §6.4 for the bias).
//
// Problem: in deep water a vehicle changes depth slowly (tens of minutes
// for a kilometre) while the objective's good depths move along range, and
// a convergence zone's caustic has its shadow zone right above it. Chasing
// the best depth of the next window (best_depth.h) keeps the vehicle in
// transit between far-apart maxima, often through a shadow.
// What the thesis asks, as we read it: stay on a ridge of high objective
// the vehicle is on; otherwise head for the optimum within the horizon it
// can reach with the least pitch without crossing a shadow zone; bias
// towards depth against caustic uncertainty. Implemented literally (one
// TARGET point: the ridge, else the earliest near-best reachable point) it
// does not meet issue 32's criterion on the deep Munk replay
// (tests/unit/eval/deep_forecast_test.cpp: 0.478 received against the next
// window's 0.752 at NL 93): a target is one point, but the packets are the
// whole path, and the straight path to a point cuts across the curving
// band of good depths that a greedy next-window choice follows.
// Decision: plan the PATH. Over the field (one column per window ahead,
// up to the forecast horizon) a dynamic programme (Viterbi) over columns ×
// depths chooses the depth at each column time that maximises the summed
// score of the windows the vehicle crosses, moving at most w·Δt between
// columns:
//   - the score is monotone in the chance of reception: the probability of
//     decoding when the caller gives the modem's reception curve with a
//     sonar-equation objective (depth_forecast_field.h), otherwise the
//     steering objective in [0, 1]. Not a linear signal excess: a path
//     with 30 dB in half its windows and 0 dB in the rest would "beat" one
//     with 15 dB throughout, yet receives half as much (a trial summing
//     the objective received 0.55 where the next window receives 0.75);
//   - a window's score is the mean of its score at the path's depths at
//     the window's start and end (the vehicle crosses it in transit);
//   - a shadow (raw objective ≤ shadow_objective) scores 0 and depths the
//     limits forbid are not on any path, so a path through a shadow zone
//     loses the windows it spends there and a lit path to the same good
//     depths wins: the thesis's "without crossing a shadow zone" as a
//     consequence, not a rule; and a ridge the vehicle is on that stays
//     high is kept because no path receives more by leaving it. A depth is
//     allowed only within the allowed interval: on a field depth, its
//     flag; between two field depths, both must be allowed (the limits may
//     lie anywhere between them; nearer the limit is refused, not risked);
//   - a vehicle outside the allowed depths (the bottom shoals under it, or
//     it reports a depth past a limit), further than a window's reach,
//     heads back: a forbidden depth may be on a path only as a step that
//     brings it nearer the allowed ones, scoring −1 (below any allowed
//     depth, so the way back is the quickest); without this every path
//     would be forbidden and it would hold where it must not be;
//   - the horizon's end is not the end of the run: beyond the last column
//     its field is assumed to last `terminal_s` more (a terminal value; by
//     default the time to cross the field's depths), so that a good band
//     out of reach within the horizon (a 3 km dive at 0.5 m/s takes 100
//     minutes) still draws the vehicle toward it. Without it the plan
//     from 20 m on the deep replay holds near the surface (nothing within
//     an hour's reach receives): 0.58-0.60 received, the earlier trial's
//     figure;
//   - the bias towards depth stays in the field: its steering objective is
//     low-passed from the surface down (spec §6.4) by the caller
//     (depth_forecast_field.h), and the score derives from it.
// The path is planned on a depth grid of its own over the field's depths
// only, from the vehicle's depth (or the field's nearest end when it is
// outside them: the model says nothing there) in steps that divide w·Δt
// (≤ 10 m, and no coarser than the field), with the field's values
// interpolated linearly, so the plan's next depth is exactly reachable.
// Ties go to the smallest move. The work is bounded whatever the request
// (any reported depth, any field, w ≤ 10 m/s; counts clamped as doubles
// before any integer cast): at most 4001 plan depths (a vehicle slower
// than a 4000th of the field's depths per column plans as if it could not
// move), 16 plan steps per reach, 127 per column, and 480 columns past
// the horizon.
// The choice reported: "ridge" when the vehicle is on a local maximum of
// the score and the whole plan stays on one (within ridge_tolerance of the
// best within a field spacing), "optimum" when the plan leaves for better
// depths (the target: the plan's best point, the earliest), "hold" when
// nothing ahead is predicted to receive.
// Invariants: every planned depth is allowed, but for the way back into
// the allowed depths (each of its steps nearer them), and reachable from
// the previous one at the vertical speed (from the vehicle's own depth
// when it is within the field's); the plan's grid has at most 4001 depths;
// the result depends on nothing but the arguments.
// Thread-safe: pure functions.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gram/range_window.h"
#include "gram/reception_curve.h"

namespace acomms::gram {

struct ForecastField {
  std::vector<double> depth_m;  // strictly increasing
  std::vector<double> time_s;   // per column, strictly increasing, time_s[0] = 0 (the window now)
  // [column][depth]: what the vehicle steers by (filtered), and the raw
  // objective that says where the shadow is; allowed: the limits.
  std::vector<std::vector<double>> steer;
  std::vector<std::vector<double>> raw;
  std::vector<std::vector<bool>> allowed;
  // [column][depth], in [0, 1], monotone in the chance of reception: what
  // the path maximises. Empty: the steering objective.
  std::vector<std::vector<double>> score;
};

struct ForecastOptions {
  double vertical_speed_mps = 0.75;  // w, in (0, 10] m/s
  // [0, 1], of the score: within it of the best nearby counts as on a
  // ridge. It only picks the label reported ("ridge" or "optimum"); the
  // plan is the same either way.
  double ridge_tolerance = 0.05;
  double shadow_objective = 0.0;     // raw objective at or below: shadow, [0, 1)
  // The terminal value: beyond the last column its field is assumed to
  // hold this many seconds more, in [0, 86400] (0: the plan ends at the
  // horizon). Unset: as long as crossing the field's depths takes at w, so
  // that any band at any depth can draw the vehicle.
  std::optional<double> terminal_s;
};

enum class ForecastChoice { kRidge, kOptimum, kHold };
const char* forecast_choice_name(ForecastChoice choice);  // "ridge", "optimum", "hold"

struct ForecastDecision {
  ForecastChoice choice = ForecastChoice::kHold;
  // The plan's best point (the earliest of its best); kHold: the vehicle's
  // depth, time 0.
  double target_depth_m = 0;
  double target_time_s = 0;
  double target_objective = 0;  // its score (0 for a depth the limits forbid)
  double vertical_rate_mps = 0;  // |target − current| / target_time_s (the mean, not the plan's rate)
  // The plan: its depth at each column's time (path_depth_m[0] = the
  // vehicle's), and its mean score per window over the horizon (forbidden
  // depths on the way back scoring 0).
  std::vector<double> path_time_s;
  std::vector<double> path_depth_m;
  double expected_score = 0;
  // Where to be `dt` seconds from now: along the plan, linearly between
  // its columns, then at its last depth.
  double depth_after(double current_depth_m, double dt) const;
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
  // The modem's reception curve (P(decode | SNR), reception_curve.h), with
  // the sonar-equation objective (SNR: its signal excess SL − H − NL + AG):
  // the plan then maximises the expected number of packets received.
  // Unset: it maximises the steering objective.
  std::optional<ReceptionCurve> reception;
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
