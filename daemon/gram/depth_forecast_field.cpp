// The forecast field from TL (see depth_forecast_field.h).
#include "gram/depth_forecast_field.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace acomms::gram {

DepthForecastResult compute_depth_forecast(std::span<const TransmissionLoss> instances, const Environment& env,
                                           const DepthObjectiveRequest& request) {
  if (!request.forecast) throw std::invalid_argument("compute_depth_forecast needs request.forecast");
  const DepthForecastRequest& f = *request.forecast;
  if (auto e = validate_depth_forecast_request(f, request.horizon_s)) throw std::invalid_argument(*e);
  if (instances.empty()) throw std::invalid_argument("the depth forecast needs at least 1 TL instance");

  DepthObjectiveRequest column = request;
  column.forecast.reset();
  if (f.caustic_uncertainty_m > 0) column.lowpass = LowpassOptions{1.0 / f.caustic_uncertainty_m, false};
  const double last_range = *std::max_element(instances[0].range_m.begin(), instances[0].range_m.end());
  const double along = request.speed_mps * std::cos(request.heading_deg * std::numbers::pi / 180.0);

  // The column requests, then their answers.
  std::vector<DepthObjectiveRequest> requests;
  const auto columns = static_cast<std::size_t>(std::floor(f.forecast_horizon_s / request.horizon_s + 1e-9));
  for (std::size_t k = 0; k <= columns; ++k) {
    column.range_m = request.range_m + along * (k * request.horizon_s);
    if (k > 0 && (column.range_m < 0 || column.range_m > last_range)) break;
    // The leg ends (a turn, the end of the run): no column past it but the next window.
    if (k > 1 && f.leg_end_range_m &&
        ((along > 0 && column.range_m > *f.leg_end_range_m) || (along < 0 && column.range_m < *f.leg_end_range_m)))
      break;
    requests.push_back(column);
  }
  std::vector<DepthObjectiveResult> answers;
  for (const DepthObjectiveRequest& q : requests) answers.push_back(compute_depth_objective(instances, env, q));

  // One scale for every column, or the planner would weigh each window
  // against itself: H_max of eq. 4.3 as the window
  // maximum becomes the largest over the horizon (the columns are run again
  // with it fixed); with the sonar equation each column's O_SE is
  // (SE − SE₀)/(SE₁ − SE₀) with its own SE₁, a positive factor away from the
  // horizon's, and the low-pass is linear, so each column is rescaled.
  if (!request.sonar && !request.h_max_db) {
    double h_max = 0;
    for (const auto& a : answers) h_max = std::max(h_max, a.h_max_db);
    if (h_max > 0)
      for (std::size_t k = 0; k < requests.size(); ++k) {
        requests[k].h_max_db = h_max;
        answers[k] = compute_depth_objective(instances, env, requests[k]);
      }
  }
  std::vector<double> scale(answers.size(), 1.0);
  double se0 = 0, top = 0;
  if (request.sonar) {
    se0 = request.sonar->threshold_db;
    std::vector<double> se1(answers.size(), -INFINITY);
    for (std::size_t k = 0; k < answers.size(); ++k)
      for (double se : answers[k].signal_excess_db) se1[k] = std::max(se1[k], se);
    top = *std::max_element(se1.begin(), se1.end());
    for (std::size_t k = 0; k < answers.size(); ++k)
      if (se1[k] > se0 && top > se0) scale[k] = (se1[k] - se0) / (top - se0);
  }

  DepthForecastResult out;
  for (std::size_t k = 0; k < answers.size(); ++k) {
    const DepthObjectiveResult& r = answers[k];
    if (k == 0) out.field.depth_m = r.depth_m;
    const double deepest = std::min(request.limits.max_depth_m, r.bottom_m - request.limits.min_altitude_m);
    std::vector<bool> allowed;
    for (double z : r.depth_m) allowed.push_back(z >= request.limits.min_depth_m && z <= deepest);
    std::vector<double> steer = r.objective_filtered, raw = r.objective;
    for (double& v : steer) v *= scale[k];
    for (double& v : raw) v *= scale[k];
    // With the modem's curve the plan weighs windows by the chance of
    // decoding: the rescaled steering objective is (SE − SE₀)/(top − SE₀),
    // linear in the (low-passed) signal excess, so SE and the SNR it is
    // follow back from it (clipped cells, SE ≤ SE₀, are shadow to the planner).
    if (f.reception && request.sonar) {
      std::vector<double> p;
      for (double v : steer)
        p.push_back(top > se0 ? reception_probability(*f.reception, se0 + v * (top - se0)) : 0.0);
      out.field.score.push_back(std::move(p));
    }
    out.field.time_s.push_back(k * request.horizon_s);
    out.field.steer.push_back(std::move(steer));
    out.field.raw.push_back(std::move(raw));
    out.field.allowed.push_back(std::move(allowed));
    out.windows.push_back(r.window);
    out.horizon_used_s = k * request.horizon_s;
  }
  out.decision = forecast_depth(out.field, f.current_depth_m, f.options);
  out.next_depth_m = out.decision.depth_after(f.current_depth_m, request.horizon_s);
  return out;
}

}  // namespace acomms::gram
