// The replay's adaptive vehicles: see depth_adaptation_vehicles.h.
#include "eval/depth_adaptation_vehicles.h"

#include <algorithm>
#include <functional>
#include <span>

namespace acomms::eval {
namespace {

double bottom_of(const gram::Environment& env) { return env.sound_speed(env.sound_speed_size() - 1).depth_m(); }

// Decisions every τ_a from t = 0 (a decision due at a packet's time comes
// first); `decide(t, depth now)` returns the new target. Between decisions
// the vehicle moves toward the target at most vertical_speed_mps.
std::vector<double> fly(const DepthAdaptationConfig& c, const std::vector<Packet>& packets,
                        std::vector<AdaptiveSample>& path, const std::function<double(double, double, double)>& decide) {
  double decided_at = 0, depth_then = c.start_depth_m, target = c.start_depth_m;
  double next_decision = 0;
  auto depth_at = [&](double t) { return move_toward(depth_then, target, c.vertical_speed_mps, t - decided_at); };
  std::vector<double> depths;
  for (const Packet& p : packets) {
    while (next_decision <= p.time_s) {
      depth_then = depth_at(next_decision);
      decided_at = next_decision;
      target = decide(next_decision, depth_then, target);
      next_decision += c.horizon_s;
    }
    depths.push_back(depth_at(p.time_s));
    path.push_back({p.time_s, p.range_m, depths.back(), target});
  }
  return depths;
}

}  // namespace

double move_toward(double from, double target, double w, double dt) {
  const double step = w * dt;
  return from + std::clamp(target - from, -step, step);
}

gram::DepthObjectiveRequest vehicle_request(const DepthAdaptationConfig& c, const gram::Environment& env) {
  gram::DepthObjectiveRequest request;
  request.speed_mps = c.speed_mps;
  request.horizon_s = c.horizon_s;
  request.h_max_db = c.h_max_db;
  request.limits = c.limits;
  if (request.limits.max_depth_m <= 0) request.limits.max_depth_m = bottom_of(env);
  if (c.noise_decrease_db_per_km) {
    gram::SonarOptions sonar;
    sonar.source_level_db = c.physics.source_level_db;
    sonar.noise_level_db = c.physics.noise_level_db;
    sonar.noise_decrease_db_per_km = c.noise_decrease_db_per_km;
    sonar.site = c.physics.site;
    sonar.threshold_db = 0;
    request.sonar = sonar;
  }
  return request;
}

std::vector<double> next_window_depths(const gram::TransmissionLoss& tl, const gram::Environment& env,
                                       const DepthAdaptationConfig& c, const Run& run,
                                       const std::vector<Packet>& packets, std::vector<AdaptiveSample>& path) {
  gram::DepthObjectiveRequest request = vehicle_request(c, env);
  const std::span<const gram::TransmissionLoss> instances(&tl, 1);
  return fly(c, packets, path, [&](double t, double, double target) {
    request.range_m = run.range(t);
    request.heading_deg = run.heading_deg(t);
    const gram::DepthObjectiveResult answer = gram::compute_depth_objective(instances, env, request);
    // No depth predicted to receive: keep the plan rather than dive on a 0.
    return answer.best.any_signal ? answer.best.depth_m : target;
  });
}

std::vector<double> forecast_depths(const gram::TransmissionLoss& tl, const gram::Environment& env,
                                    const DepthAdaptationConfig& c, const Run& run, const std::vector<Packet>& packets,
                                    std::vector<AdaptiveSample>& path) {
  gram::DepthObjectiveRequest request = vehicle_request(c, env);
  request.forecast = gram::DepthForecastRequest{};
  request.forecast->forecast_horizon_s = c.forecast_horizon_s;
  request.forecast->caustic_uncertainty_m = c.caustic_uncertainty_m;
  request.forecast->options.vertical_speed_mps = c.vertical_speed_mps;
  // The modem's reception curve (the vehicle knows its own modem, as it
  // knows SL and NL): the plan maximises the expected packets received.
  if (request.sonar) request.forecast->reception = c.physics.curve(c.rate);
  const std::span<const gram::TransmissionLoss> instances(&tl, 1);
  return fly(c, packets, path, [&](double t, double depth, double) {
    request.range_m = run.range(t);
    request.heading_deg = run.heading_deg(t);
    request.forecast->current_depth_m = depth;
    request.forecast->leg_end_range_m = t < run.t_turn() ? run.r1 : run.r0;
    const gram::DepthObjectiveResult answer = gram::compute_depth_objective(instances, env, request);
    return answer.forecast->next_depth_m;
  });
}

}  // namespace acomms::eval
