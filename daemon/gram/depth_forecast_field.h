// The forecast strategy's field (depth_forecast.h) from the model's TL: the
// depth objective (depth_objective.h) of each window the vehicle will cross
// within the forecast horizon.
//
// Problem: the forecast needs the objective not only over the next window
// but over every window up to tens of minutes ahead, computed exactly as
// the next window's is (same instances, limits, objective and sonar
// equation). Decision: column k is the query itself with the range moved
// to r₀ + |v₀| cos Θ k τ_a (k = 0, 1, ... while k τ_a ≤ the forecast
// horizon), stopping at the first column whose range leaves the model grid
// (beyond its last range, or below 0 when closing) or, after the next
// window, passes the end of the vehicle's leg (request.forecast's
// leg_end_range_m: where it turns, so the windows past it are not its). Its steering objective
// is low-passed from the surface down with cutoff 1/caustic_uncertainty_m
// (spec §6.4: the bias towards depth, below a caustic whose depth is known
// only to about 50 m), or with the query's own low-pass when that is 0; the
// shadow test reads the raw objective. Allowed depths: the query's limits
// with the bottom under each column's window. The columns share one scale:
// where the objective is relative to a window's maximum (H_max as the window
// maximum, or the sonar equation's SE₁), the maximum over the horizon is
// used, so that the planner weighs the windows on one scale (a window whose
// best is weak does not score as high as the horizon's best).
// The score the planner gathers (depth_forecast.h): with the sonar
// equation and the modem's reception curve (request.forecast's
// `reception`), the probability of decoding at each cell's low-passed
// signal excess, read back from the rescaled steering objective, which is
// linear in it: (SE − SE₀)/(SE_top − SE₀); otherwise none (the planner
// gathers the steering objective itself).
// Thread-safe: pure function of its arguments.
#pragma once

#include <span>

#include "gram/depth_forecast.h"
#include "gram/depth_objective.h"

namespace acomms::gram {

// `request.forecast` must be set. Throws std::invalid_argument naming the
// field (validation) or when the grid holds not even the first window.
DepthForecastResult compute_depth_forecast(std::span<const TransmissionLoss> instances, const Environment& env,
                                           const DepthObjectiveRequest& request);

}  // namespace acomms::gram
