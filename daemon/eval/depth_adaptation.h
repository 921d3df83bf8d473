#pragma once
// The depth-adaptation experiment of Schneider (2013, §4.3, GLINT10)
// replayed offline: does a vehicle that steers toward the depth the model
// predicts least transmission loss for get more messages through than one
// that holds a fixed depth — on THIS environment?
//
// Scenario (simulated clock, no daemon): a buoy modem at a fixed depth at
// range 0; a vehicle leaves from start_range_m, runs straight out to
// max_range_m and back at speed_mps, sending one packet every
// send_interval_s at `rate`. Each packet decodes with the probability the
// physics gives (gram/link_physics.h): SNR = SL − TL − NL, TL from ONE model
// run with the source at the buoy (reciprocity: the loss from the vehicle to
// the buoy equals the loss from the buoy to the vehicle), interpolated at
// the vehicle's range and depth (gram/tl_lookup.h).
// Strategies: each fixed depth; "forecast" when asked (config.forecast: the
// deep-water strategy of gram/depth_forecast.h, deciding on the same model
// and cadence); and "adaptive" (the next window): every horizon_s (τ_a) the
// vehicle asks the depth objective (gram/depth_objective.h, eq. 4.3 with
// H_max) for the best depth over its range window (eq. 4.1 from its speed
// and heading: Θ = 0 going out, 180° coming back) and moves toward it at
// most vertical_speed_mps; with no depth predicted to receive it keeps its
// last target.
// The adaptive vehicle's model is the water itself (the same TL grid)
// unless a separate vehicle model is given (another environment: the
// profile the vehicle believes, a guessed bottom): without one this
// measures what adaptation can give with a perfect model.
// Determinism: each lap draws one uniform number per packet from a seeded
// generator, and every strategy uses the SAME numbers (common random
// numbers), so strategies differ only by their physics; the expected
// receipt (mean modelled probability) is reported beside the draws, free of
// sampling noise. Same config and environment, same output, any build.
//
// Thread-safe: an evaluation shares nothing with another (its model runs on
// threads of its own, `threads`).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "gram/best_depth.h"
#include "gram/link_physics.h"
#include "gram/transmission_loss.h"

namespace acomms::eval {

struct DepthAdaptationConfig {
  double buoy_depth_m = 30;
  double start_range_m = 50;
  double max_range_m = 3000;
  double speed_mps = 1.5;
  double send_interval_s = 30;
  std::int32_t rate = 0;
  std::vector<double> fixed_depths_m = {10, 30, 50, 70, 90};
  double start_depth_m = 30;  // the adaptive vehicle's depth when it leaves
  double vertical_speed_mps = 0.75;
  double horizon_s = 120;  // τ_a: how often the best depth is recomputed
  double h_max_db = 108;   // eq. 4.3 (GLINT10)
  // max_depth_m 0: no rating limit, only the altitude above the bottom.
  gram::VehicleLimits limits{5.0, 0.0, 10.0};
  double bin_m = 400;  // range bins of the report (the thesis's Fig. 4.7d)
  // The model's receiver grid (the environment file's grid is replaced).
  double range_step_m = 10;
  double depth_step_m = 0;  // 0: gram::default_depth_step_m (2 m in shallow water)
  std::uint32_t laps = 20;  // repetitions of the run, each with fresh draws
  std::uint64_t seed = 1;
  gram::LinkPhysics physics;  // SL, NL and the reception curves
  unsigned threads = 0;       // model threads (0: all cores); same result
  // Deep water: NL falls by this many dB/km below the profile's critical
  // depth (gram/noise_depth_profile.h, spec §6.6) for every packet; the
  // adaptive vehicles then rank depths by the sonar equation's signal
  // excess (SE₀ = 0 dB) instead of eq. 4.3. Unset: NL the same at every depth.
  std::optional<double> noise_decrease_db_per_km;
  // The forecast strategy (gram/depth_forecast.h), run beside the others
  // when set: every horizon_s it forecasts the objective up to
  // forecast_horizon_s ahead and heads for the depth its plan puts it at
  // by the next decision.
  bool forecast = false;
  double forecast_horizon_s = 3600;  // an hour: 2.7 km of depth at 0.75 m/s
  double caustic_uncertainty_m = 50;  // 0: no low-pass of the steering objective
};

struct StrategyResult {
  std::string name;  // "10 m", ..., "forecast", "adaptive"
  std::optional<double> fixed_depth_m;
  std::vector<std::uint32_t> sent, received;  // per range bin, over all laps
  std::vector<double> expected;               // per bin: mean modelled probability
  std::uint32_t total_sent = 0, total_received = 0;
  double expected_overall = 0;
  double mean_depth_m = 0;  // over the packets sent
  double receipt(std::size_t bin) const { return sent[bin] ? double(received[bin]) / sent[bin] : 0.0; }
  double receipt_overall() const { return total_sent ? double(total_received) / total_sent : 0.0; }
};

// The adaptive vehicle's path, one point per packet (one lap).
struct AdaptiveSample {
  double time_s = 0, range_m = 0, depth_m = 0, target_m = 0;
};

struct DepthAdaptationResult {
  std::vector<double> bin_edges_m;          // bins [e_i, e_{i+1})
  std::vector<StrategyResult> strategies;   // fixed depths in order, forecast if asked, adaptive last
  std::vector<AdaptiveSample> forecast_path;  // the forecast vehicle's, if asked
  std::vector<AdaptiveSample> adaptive_path;
  std::uint32_t beam_count = 0;
  double noise_level_db = 0;
  std::size_t model_ranges = 0, model_depths = 0;
  // The verdicts: on the draws, strictly more packets than every fixed
  // depth; on the expectation, more by over 0.001 (a tenth of a point).
  bool adaptive_beats_every_fixed = false;
  bool adaptive_expected_beats_every_fixed = false;
  std::size_t best_fixed = 0;  // index of the fixed depth receiving most (draws)
  std::optional<double> critical_depth_m;  // with a noise decrease: where NL starts to fall
  bool separate_model = false;  // the vehicle decided on its own model
};

// Throws std::invalid_argument naming the field and bound (config, or an
// environment the model refuses).
// `vehicle_model`: the environment the adaptive vehicle believes (null: the
// water itself); its grid is built the same way.
DepthAdaptationResult run_depth_adaptation(const gram::Environment& env, const DepthAdaptationConfig& config,
                                           const gram::Environment* vehicle_model = nullptr);

// The same in two steps, for a caller that replays one geometry under
// several physics (a sweep of the noise or the excess loss: the packets'
// fate changes, the model's transmission loss does not). The model holds
// the config it was made with; a replay takes only the physics from its
// argument.
struct DepthAdaptationModel {
  DepthAdaptationConfig config;
  gram::Environment env;  // with the experiment's grid
  gram::TransmissionLoss tl;
  std::optional<gram::Environment> believed;  // the vehicle's own model, if any
  std::optional<gram::TransmissionLoss> believed_tl;
};
DepthAdaptationModel model_depth_adaptation(const gram::Environment& env, const DepthAdaptationConfig& config,
                                            const gram::Environment* vehicle_model = nullptr);
DepthAdaptationResult replay_depth_adaptation(const DepthAdaptationModel& model, const gram::LinkPhysics& physics);

// The standard error of a strategy's overall receipt p over its n packets:
// sqrt(p (1 − p) / n) (the laps share nothing but the path).
double receipt_se(const StrategyResult& strategy);

// The per-bin table (one row per strategy, with the overall receipt's SE)
// and the verdict, for people.
std::string format_depth_adaptation_table(const DepthAdaptationConfig& config, const DepthAdaptationResult& result);
std::string format_depth_adaptation_json(const DepthAdaptationConfig& config, const DepthAdaptationResult& result);

}  // namespace acomms::eval
