// The depth objective of GRAM (Schneider (2013) ch. 4, spec §6): which
// depth should the vehicle hold to hear the other node over the next τ_a
// seconds?
//
// Problem: the model gives TL on a grid for each measured sound-speed
// profile; the vehicle needs one depth. Decision, in this order:
//   1. the range window from speed, heading and horizon (eq. 4.1,
//      range_window.h), widened to one grid spacing if shorter;
//   2. H(d, i): TL averaged in intensity over the window for each profile
//      instance i (eq. 4.2, range_averaged_tl.h), then H̄(d) over the
//      instances (eq. 4.4) with its sensitivity band;
//   3. the objective: eq. 4.3 with a fixed H_max or the window maximum; or,
//      when sonar options are given, the signal-excess objective of eq. 4.7
//      (sonar_equation.h), which then replaces eq. 4.3 (a window maximum
//      ≤ 0 dB, a gain everywhere, scores every depth 1); NL may fall below
//      the profile's critical depth (noise_depth_profile.h);
//   4. optionally the low-pass over depth (§6.4, depth_lowpass.h), run from
//      the shallowest ALLOWED depth down over the allowed depths (resampled
//      to ≤ 10 m if uneven or coarse); depths outside the limits keep their
//      raw value;
//   5. the best allowed depth (best_depth.h; ties to the shallowest);
//   6. if asked, the forecast strategy (depth_forecast_field.h).
// Every instance must share the receiver grid. All request fields are
// validated first; an error names the field and the bound.
// Thread-safe: pure function of its arguments.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "gram/best_depth.h"
#include "gram/depth_forecast.h"
#include "gram/depth_lowpass.h"
#include "gram/range_averaged_tl.h"
#include "gram/range_window.h"
#include "gram/sonar_equation.h"
#include "gram/transmission_loss.h"

namespace acomms::gram {

struct DepthObjectiveRequest {
  double range_m = 0;      // r₀
  double speed_mps = 0;    // |v₀|
  double heading_deg = 0;  // Θ, 0 = straight away from the other node
  double horizon_s = 120;  // τ_a
  // H_max of eq. 4.3 (> 0), or unset for the window maximum of H̄.
  std::optional<double> h_max_db = 108.0;
  VehicleLimits limits;
  std::optional<LowpassOptions> lowpass;
  std::optional<SonarOptions> sonar;
  // Deep water: also forecast over the windows ahead and plan a depth path
  // (depth_forecast_field.h); unset: the next window only.
  std::optional<DepthForecastRequest> forecast;
};

struct DepthObjectiveResult {
  RangeWindow window;
  std::size_t ranges_in_window = 0;
  std::vector<double> depth_m;
  std::vector<double> h_bar_db;     // eq. 4.4 over the instances (eq. 4.2 if one)
  std::vector<double> band_low_db;  // sensitivity band of eq. 4.4
  std::vector<double> band_high_db;
  double h_max_db = 0;                     // the H_max used (eq. 4.3 objective only)
  std::optional<double> critical_depth_m;  // sonar with a noise decrease only
  std::vector<double> noise_level_db;      // per depth, sonar only
  std::vector<double> signal_excess_db;    // per depth, sonar only
  std::vector<double> objective;           // raw: eq. 4.3, or O_SE with sonar
  std::vector<double> objective_filtered;  // after §6.4 (equals `objective` without lowpass)
  double bottom_m = 0;                     // shallowest bottom under the window
  BestDepth best;
  std::optional<DepthForecastResult> forecast;  // when the request asked for one
};

std::optional<std::string> validate_depth_objective_request(const DepthObjectiveRequest& request);

// `instances`: one TL grid per sound-speed profile, same grid. `env` gives
// the bathymetry (the altitude limit). Throws std::invalid_argument.
DepthObjectiveResult compute_depth_objective(std::span<const TransmissionLoss> instances,
                                             const Environment& env,
                                             const DepthObjectiveRequest& request);

}  // namespace acomms::gram
