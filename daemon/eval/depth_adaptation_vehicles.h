#pragma once
// The adaptive vehicles of the depth-adaptation replay (depth_adaptation.h):
// where each puts itself, packet by packet, on one lap.
//
// Problem: the replay compares strategies that differ only in how they pick
// their depth; they must see the same model, decide at the same cadence
// (every τ_a), move under the same vertical speed limit, and ask the same
// objective. Decision: one request builder for both, and one function per
// strategy returning the vehicle's depth at each packet:
//   - next window ("adaptive", Schneider (2013) §4.3): the best depth of
//     the next window (gram/depth_objective.h), approached at full vertical
//     speed; with nothing predicted to receive it keeps its last target;
//   - forecast (§4.4, gram/depth_forecast.h): the path planned over the
//     forecast horizon (with the modem's reception curve when it ranks by
//     the sonar equation, so the plan maximises the packets it expects);
//     it heads for the depth the plan puts it at by the next decision
//     (reachable by construction, so within the vertical speed). Its
//     leg ends at the turn (going out) or at the start range (coming
//     back): the forecast does not look at windows it will not cross.
// With a noise decrease over depth the objective is the sonar equation's
// signal excess (H̄ alone is no proxy for SNR when NL varies with depth,
// spec §6.6); otherwise eq. 4.3 with H_max.
// Internal to the replay. Thread-safe: pure functions.

#include <cstddef>
#include <vector>

#include "eval/depth_adaptation.h"
#include "gram/depth_objective.h"

namespace acomms::eval {

// The vehicle's run: out from r0 to r1 at v, then back.
struct Run {
  double r0, r1, v;
  double t_turn() const { return (r1 - r0) / v; }
  double t_end() const { return 2 * t_turn(); }
  double range(double t) const { return t <= t_turn() ? r0 + v * t : r1 - v * (t - t_turn()); }
  double heading_deg(double t) const { return t < t_turn() ? 0.0 : 180.0; }
};

struct Packet {
  double time_s, range_m;
  std::size_t bin;
};

// Depth after moving from `from` toward `target` for `dt` at `w` m/s at most.
double move_toward(double from, double target, double w, double dt);

// The depth objective request the vehicles share (range and heading are
// set at each decision).
gram::DepthObjectiveRequest vehicle_request(const DepthAdaptationConfig& c, const gram::Environment& env);

std::vector<double> next_window_depths(const gram::TransmissionLoss& tl, const gram::Environment& env,
                                       const DepthAdaptationConfig& c, const Run& run,
                                       const std::vector<Packet>& packets, std::vector<AdaptiveSample>& path);

std::vector<double> forecast_depths(const gram::TransmissionLoss& tl, const gram::Environment& env,
                                    const DepthAdaptationConfig& c, const Run& run, const std::vector<Packet>& packets,
                                    std::vector<AdaptiveSample>& path);

}  // namespace acomms::eval
