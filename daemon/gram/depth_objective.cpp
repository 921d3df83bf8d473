// The depth objective pipeline: shared/spec/gram.md §6.
#include "gram/depth_objective.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gram/depth_forecast_field.h"
#include "gram/loss_objective.h"
#include "gram/noise_depth_profile.h"
#include "gram/validation_text.h"

namespace acomms::gram {
namespace {

void require_same_grid(std::span<const TransmissionLoss> instances) {
  if (instances.empty())
    throw std::invalid_argument("the depth objective needs at least 1 TL instance");
  for (std::size_t i = 1; i < instances.size(); ++i)
    if (instances[i].range_m != instances[0].range_m ||
        instances[i].depth_m != instances[0].depth_m)
      throw std::invalid_argument("TL instance " + std::to_string(i) +
                                  " has a different receiver grid from instance 0");
}

void combine_instances(std::span<const TransmissionLoss> instances, const RangeWindow& window,
                       DepthObjectiveResult& out) {
  std::vector<RangeAveragedTl> per;
  for (const auto& tl : instances) per.push_back(range_averaged_tl(tl, window));
  out.depth_m = per[0].depth_m;
  out.ranges_in_window = per[0].ranges_in_window;
  std::vector<double> h(per.size());
  for (std::size_t d = 0; d < out.depth_m.size(); ++d) {
    for (std::size_t i = 0; i < per.size(); ++i) h[i] = per[i].h_bar_db[d];
    const InstanceAverage a = average_over_instances(h);
    out.h_bar_db.push_back(a.h_n_db);
    out.band_low_db.push_back(a.band_low_db);
    out.band_high_db.push_back(a.band_high_db);
  }
}

void compute_objective(const DepthObjectiveRequest& request, const Environment& env,
                       DepthObjectiveResult& out) {
  if (!request.sonar) {
    if (request.h_max_db) {
      out.h_max_db = *request.h_max_db;
    } else if (auto m = window_maximum(out.h_bar_db)) {
      out.h_max_db = *m;
    } else {
      out.h_max_db = 0;  // every depth in shadow: nothing to score
      out.objective.assign(out.depth_m.size(), 0.0);
      return;
    }
    if (!(out.h_max_db > 0))  // a window maximum ≤ 0 dB: gain, not loss; score all 1
      out.objective.assign(out.depth_m.size(), 1.0);
    else
      out.objective = loss_objective(out.h_bar_db, out.h_max_db);
    return;
  }
  const SonarOptions& s = *request.sonar;
  const double nl0 = noise_level_db(s);
  if (s.noise_decrease_db_per_km) out.critical_depth_m = critical_depth(env);
  for (std::size_t i = 0; i < out.depth_m.size(); ++i) {
    // The ambient level may fall with depth; the vehicle's own noise travels
    // with it (site_correction.h).
    const double nl = s.site.total_noise_db(noise_level_at_depth(nl0, out.depth_m[i], out.critical_depth_m,
                                                                 s.noise_decrease_db_per_km.value_or(0.0)));
    out.noise_level_db.push_back(nl);
    out.signal_excess_db.push_back(
        signal_excess_db(s.source_level_db, out.h_bar_db[i] + s.site.excess_loss_db, nl, s.array_gain_db));
  }
  out.objective = signal_excess_objective(out.signal_excess_db, s.threshold_db);
}

// §6.4 over the allowed depths, from the shallowest allowed down.
void filter_objective(const DepthObjectiveRequest& request, DepthObjectiveResult& out) {
  out.objective_filtered = out.objective;
  if (!request.lowpass) return;
  const double deepest =
      std::min(request.limits.max_depth_m, out.bottom_m - request.limits.min_altitude_m);
  std::vector<std::size_t> allowed;
  for (std::size_t i = 0; i < out.depth_m.size(); ++i)
    if (out.depth_m[i] >= request.limits.min_depth_m && out.depth_m[i] <= deepest)
      allowed.push_back(i);
  // The filter runs downward whatever order the receiver depths were given in.
  std::stable_sort(allowed.begin(), allowed.end(),
                   [&](std::size_t a, std::size_t b) { return out.depth_m[a] < out.depth_m[b]; });
  std::vector<double> depths, values;
  for (std::size_t i : allowed) {
    depths.push_back(out.depth_m[i]);
    values.push_back(out.objective[i]);
  }
  const std::vector<double> y = lowpass_on_depths(depths, values, *request.lowpass);
  for (std::size_t k = 0; k < allowed.size(); ++k) out.objective_filtered[allowed[k]] = y[k];
}

}  // namespace

std::optional<std::string> validate_depth_objective_request(const DepthObjectiveRequest& r) {
  if (auto e = require_at_least("range_m", r.range_m, 0.0)) return e;
  if (auto e = require_at_least("speed_mps", r.speed_mps, 0.0)) return e;
  if (auto e = require_finite("heading_deg", r.heading_deg)) return e;
  if (auto e = require_greater("horizon_s", r.horizon_s, 0.0)) return e;
  if (r.h_max_db)
    if (auto e = require_greater("h_max_db", *r.h_max_db, 0.0)) return e;
  if (auto e = validate_limits(r.limits)) return e;
  if (r.lowpass)
    if (auto e = validate_lowpass(*r.lowpass)) return e;
  if (r.sonar)
    if (auto e = validate_sonar(*r.sonar)) return e;
  if (r.forecast) {
    if (auto e = validate_depth_forecast_request(*r.forecast, r.horizon_s)) return e;
    // The curve reads the SNR from the sonar equation's signal excess:
    // without it there is no SNR, and the curve would be ignored.
    if (r.forecast->reception && !r.sonar)
      return "reception_snr50_db needs the sonar equation (sonar): the reception curve is read at its signal excess";
  }
  return std::nullopt;
}

DepthObjectiveResult compute_depth_objective(std::span<const TransmissionLoss> instances,
                                             const Environment& env,
                                             const DepthObjectiveRequest& request) {
  if (auto e = validate_depth_objective_request(request)) throw std::invalid_argument(*e);
  if (env.sound_speed_size() < 1)
    throw std::invalid_argument("the environment has no sound_speed points (its bottom depth)");
  require_same_grid(instances);
  DepthObjectiveResult out;
  out.window = range_window({request.range_m, request.speed_mps, request.heading_deg,
                             request.horizon_s, grid_range_step(instances[0])});
  combine_instances(instances, out.window, out);
  out.bottom_m = shallowest_bottom(env, out.window);
  compute_objective(request, env, out);
  filter_objective(request, out);
  out.best = best_depth(out.depth_m, out.objective_filtered, request.limits, out.bottom_m);
  if (request.forecast) out.forecast = compute_depth_forecast(instances, env, request);
  return out;
}

}  // namespace acomms::gram
