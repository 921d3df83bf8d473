// The GLINT10 depth-adaptation experiment: see depth_adaptation.h.
#include "eval/depth_adaptation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "eval/depth_adaptation_vehicles.h"
#include "gram/depth_objective.h"
#include "gram/noise_depth_profile.h"
#include "gram/tl_lookup.h"
#include "gram/transmission_loss.h"
#include "gram/validation_text.h"

namespace acomms::eval {
namespace {


// "More" in expectation means more by a tenth of a percentage point: a
// strategy whose packets already decode with p = 1 − 1e-9 does not "help".
constexpr double kExpectationTie = 1e-3;
using gram::require_at_least;
using gram::require_greater;

void check(std::optional<std::string> problem) {
  if (problem) throw std::invalid_argument(*problem);
}

double surface_of(const gram::Environment& env) { return env.sound_speed(0).depth_m(); }
double bottom_of(const gram::Environment& env) { return env.sound_speed(env.sound_speed_size() - 1).depth_m(); }

double depth_step(const gram::Environment& env, const DepthAdaptationConfig& c) {
  return c.depth_step_m > 0 ? c.depth_step_m : gram::default_depth_step_m(bottom_of(env) - surface_of(env));
}

// How far ahead of the vehicle the model grid must reach, in time.
double looked_ahead_s(const DepthAdaptationConfig& c) {
  return c.forecast ? std::max(c.horizon_s, c.forecast_horizon_s) : c.horizon_s;
}

// What a replay may change without a new model run (depth_adaptation.h).
void check_physics(const DepthAdaptationConfig& c) {
  check(gram::require_finite("source_level_db", c.physics.source_level_db));
  check(gram::require_finite("noise_level_db", c.physics.noise_level_db));
  check(gram::validate_site_correction(c.physics.site, ""));
}

void validate(const gram::Environment& env, const DepthAdaptationConfig& c) {
  if (env.sound_speed_size() < 2) throw std::invalid_argument("the environment has no sound speed profile");
  const double top = surface_of(env), bottom = bottom_of(env);
  auto inside = [&](const std::string& name, double z) {
    if (!(z > top && z < bottom))
      throw std::invalid_argument(name + " = " + gram::format_number(z) + " must lie in the water column (" +
                                  gram::format_number(top) + ", " + gram::format_number(bottom) + ") m");
  };
  inside("buoy_depth_m", c.buoy_depth_m);
  inside("start_depth_m", c.start_depth_m);
  if (c.fixed_depths_m.empty()) throw std::invalid_argument("fixed_depths_m: give at least one fixed depth");
  for (double z : c.fixed_depths_m) inside("fixed_depths_m", z);
  gram::VehicleLimits limits = c.limits;
  if (limits.max_depth_m <= 0) limits.max_depth_m = bottom;  // 0: the bottom (less the altitude) limits
  check(gram::validate_limits(limits));
  check(require_greater("start_range_m", c.start_range_m, 0));
  check(require_greater("max_range_m", c.max_range_m, c.start_range_m));
  if (c.max_range_m > 200000) throw std::invalid_argument("max_range_m must be at most 200000 m");
  check(require_greater("speed_mps", c.speed_mps, 0));
  check(require_greater("send_interval_s", c.send_interval_s, 0));
  check(require_greater("vertical_speed_mps", c.vertical_speed_mps, 0));
  check(require_greater("horizon_s", c.horizon_s, 0));
  if (c.noise_decrease_db_per_km) check(require_at_least("noise_decrease_db_per_km", *c.noise_decrease_db_per_km, 0));
  if (c.forecast) {
    check(require_at_least("forecast_horizon_s", c.forecast_horizon_s, c.horizon_s));
    if (c.forecast_horizon_s / c.horizon_s > gram::kMaxForecastColumns)
      throw std::invalid_argument("forecast_horizon_s must be at most " + gram::format_number(gram::kMaxForecastColumns) +
                                  " times horizon_s");
    check(require_at_least("caustic_uncertainty_m", c.caustic_uncertainty_m, 0));
  }
  check(require_greater("h_max_db", c.h_max_db, 0));
  check(require_greater("bin_m", c.bin_m, 0));
  check(require_greater("range_step_m", c.range_step_m, 0));
  check(require_at_least("depth_step_m", c.depth_step_m, 0));
  check_physics(c);
  if (c.laps < 1 || c.laps > 100000) throw std::invalid_argument("laps must be in 1..100000");
  const double duration = 2 * (c.max_range_m - c.start_range_m) / c.speed_mps;
  if (duration / c.send_interval_s > 1e6) throw std::invalid_argument("more than 1e6 packets per lap: raise send_interval_s");
  if ((c.max_range_m + c.speed_mps * looked_ahead_s(c)) / c.range_step_m > 20000)
    throw std::invalid_argument("range_step_m is too fine: more than 20000 model ranges");
  if ((bottom - top) / depth_step(env, c) > 2000)
    throw std::invalid_argument("depth_step_m is too fine: more than 2000 model depths");
}

// The environment with the buoy as the source and the experiment's grid.
gram::Environment model_environment(gram::Environment env, const DepthAdaptationConfig& c) {
  env.set_source_depth_m(c.buoy_depth_m);
  env.set_irregular_receivers(false);
  env.clear_receiver_depth_m();
  env.clear_receiver_range_m();
  const double top = surface_of(env), bottom = bottom_of(env);
  const double dz = depth_step(env, c);
  const auto nz = static_cast<std::size_t>(std::ceil((bottom - top) / dz - 1e-9));
  for (std::size_t i = 0; i <= nz; ++i) env.add_receiver_depth_m(std::min(bottom, top + i * dz));
  // Out to the farthest range window the vehicle will ask about.
  const double r_end = c.max_range_m + c.speed_mps * looked_ahead_s(c) + c.range_step_m;
  const auto nr = static_cast<std::size_t>(std::ceil(r_end / c.range_step_m));
  for (std::size_t i = 0; i <= nr; ++i) env.add_receiver_range_m(i * c.range_step_m);
  // Rays that leave the file's box stop; the box must hold the new grid.
  env.set_box_range_m(std::max(env.box_range_m(), (nr + 1) * c.range_step_m));
  env.set_box_depth_m(std::max(env.box_depth_m(), bottom + 1));
  return env;
}

}  // namespace

DepthAdaptationModel model_depth_adaptation(const gram::Environment& file_env, const DepthAdaptationConfig& c,
                                            const gram::Environment* vehicle_model) {
  validate(file_env, c);
  if (vehicle_model) validate(*vehicle_model, c);
  DepthAdaptationModel model;
  model.config = c;
  model.env = model_environment(file_env, c);
  model.tl = gram::compute_transmission_loss(model.env, {c.threads});
  // The vehicle decides on its own model when it has one, the water decides.
  if (vehicle_model) {
    model.believed = model_environment(*vehicle_model, c);
    model.believed_tl = gram::compute_transmission_loss(*model.believed, {c.threads});
  }
  return model;
}

DepthAdaptationResult run_depth_adaptation(const gram::Environment& file_env, const DepthAdaptationConfig& c,
                                           const gram::Environment* vehicle_model) {
  return replay_depth_adaptation(model_depth_adaptation(file_env, c, vehicle_model), c.physics);
}

DepthAdaptationResult replay_depth_adaptation(const DepthAdaptationModel& model, const gram::LinkPhysics& physics) {
  DepthAdaptationConfig c = model.config;
  c.physics = physics;
  check_physics(c);
  const gram::Environment& env = model.env;
  const gram::TransmissionLoss& tl = model.tl;
  const std::optional<gram::Environment>& believed = model.believed;
  const std::optional<gram::TransmissionLoss>& believed_tl = model.believed_tl;

  DepthAdaptationResult out;
  out.beam_count = tl.beam_count;
  out.noise_level_db = c.physics.noise_level_db;
  out.model_ranges = tl.range_m.size();
  out.model_depths = tl.depth_m.size();
  const auto bins = static_cast<std::size_t>(std::ceil(c.max_range_m / c.bin_m - 1e-9));
  for (std::size_t i = 0; i <= bins; ++i) out.bin_edges_m.push_back(i * c.bin_m);

  const Run run{c.start_range_m, c.max_range_m, c.speed_mps};
  std::vector<Packet> packets;
  for (std::size_t m = 0;; ++m) {
    const double t = m * c.send_interval_s;
    if (t > run.t_end() + 1e-9) break;
    const double r = run.range(t);
    packets.push_back({t, r, std::min(bins - 1, static_cast<std::size_t>(r / c.bin_m))});
  }

  // Depth of each packet, per strategy.
  std::vector<std::vector<double>> depth_of;
  for (double z : c.fixed_depths_m) {
    depth_of.emplace_back(packets.size(), z);
    char name[32];
    std::snprintf(name, sizeof name, "%g m", z);
    out.strategies.push_back({name, z, {}, {}, {}});
  }
  // The vehicles decide on their own model when they have one.
  const gram::TransmissionLoss& decide_tl = believed ? *believed_tl : tl;
  const gram::Environment& decide_env = believed ? *believed : env;
  if (c.forecast) {
    depth_of.push_back(forecast_depths(decide_tl, decide_env, c, run, packets, out.forecast_path));
    out.strategies.push_back({"forecast", std::nullopt, {}, {}, {}});
  }
  depth_of.push_back(next_window_depths(decide_tl, decide_env, c, run, packets, out.adaptive_path));
  out.separate_model = believed.has_value();
  out.strategies.push_back({"adaptive", std::nullopt, {}, {}, {}});

  // NL at each depth (the water's profile): constant unless it falls.
  if (c.noise_decrease_db_per_km) out.critical_depth_m = gram::critical_depth(env);
  auto noise_at = [&](double depth) {
    return c.noise_decrease_db_per_km ? gram::noise_level_at_depth(physics.noise_level_db, depth, out.critical_depth_m,
                                                                   *c.noise_decrease_db_per_km)
                                      : physics.noise_level_db;
  };
  gram::LinkPhysics at_depth = c.physics;

  // One uniform number per packet and lap, shared by every strategy.
  std::mt19937_64 rng(c.seed);
  std::vector<double> draws(packets.size() * c.laps);
  for (double& u : draws) u = static_cast<double>(rng() >> 11) * 0x1.0p-53;  // 53 bits: same on every library

  for (std::size_t s = 0; s < out.strategies.size(); ++s) {
    StrategyResult& result = out.strategies[s];
    result.sent.assign(bins, 0);
    result.received.assign(bins, 0);
    result.expected.assign(bins, 0.0);
    std::vector<double> p(packets.size());
    double depth_sum = 0;
    for (std::size_t k = 0; k < packets.size(); ++k) {
      const double tl_db = gram::tl_at(tl, packets[k].range_m, depth_of[s][k]);
      at_depth.noise_level_db = noise_at(depth_of[s][k]);
      p[k] = gram::link_outcome(at_depth, tl_db, c.rate).probability;
      depth_sum += depth_of[s][k];
      result.expected[packets[k].bin] += p[k];
      result.expected_overall += p[k];
    }
    for (std::uint32_t lap = 0; lap < c.laps; ++lap)
      for (std::size_t k = 0; k < packets.size(); ++k) {
        const std::size_t bin = packets[k].bin;
        ++result.sent[bin];
        if (draws[lap * packets.size() + k] < p[k]) ++result.received[bin];
      }
    std::vector<std::uint32_t> per_lap(bins, 0);
    for (const Packet& packet : packets) ++per_lap[packet.bin];
    for (std::size_t b = 0; b < bins; ++b) {
      if (per_lap[b]) result.expected[b] /= per_lap[b];
      result.total_sent += result.sent[b];
      result.total_received += result.received[b];
    }
    result.expected_overall /= packets.size();
    result.mean_depth_m = depth_sum / packets.size();
  }

  const StrategyResult& adaptive = out.strategies.back();
  out.adaptive_beats_every_fixed = true;
  out.adaptive_expected_beats_every_fixed = true;
  for (std::size_t s = 0; s < out.strategies.size(); ++s) {
    const StrategyResult& fixed = out.strategies[s];
    if (!fixed.fixed_depth_m) continue;
    if (fixed.total_received > out.strategies[out.best_fixed].total_received) out.best_fixed = s;
    if (fixed.total_received >= adaptive.total_received) out.adaptive_beats_every_fixed = false;
    if (fixed.expected_overall >= adaptive.expected_overall - kExpectationTie) out.adaptive_expected_beats_every_fixed = false;
  }
  return out;
}

}  // namespace acomms::eval
