#pragma once
// The error of a vehicle's own navigation solution between position fixes
// (realistic_track.h): what the vehicle logs, and so what telemetry sends,
// is its estimate, not where it is.
//
// Submerged, a vehicle dead-reckons: a torpedo AUV integrates its DVL's
// velocity over ground in its INS, a glider its flight model's speed through
// the water plus the current it last estimated. The error grows with the
// distance run, from three causes, drawn afresh for every dive:
//   scale     the speed reads a fraction too high or low (DVL scale factor,
//             a glider's flight model): an along-track drift
//   heading   a compass or INS heading bias: a cross-track drift, bias x
//             distance
//   random    a slowly wandering velocity error (Gauss-Markov)
// plus whatever velocity the caller adds (a glider's mis-estimated current).
// At the surface a GPS fix corrects it: the error jumps to the GPS's own
// (a few metres) and then wanders with it while the fixes continue. The
// jump is what the telemetry sees as a step of tens (AUV) or hundreds
// (glider) of metres.
//
// Not thread-safe: one track's state.

#include <array>

#include "eval/track_math.h"

namespace acomms::eval {

struct NavigationErrorParams {
  double scale_sigma = 0.002;          // fraction of speed
  double heading_bias_sigma_rad = 0.0017;
  double random_sigma_mps = 0.003;
  double random_tau_s = 900;
  double gps_sigma_m = 2;             // the first fix's error
  double gps_wander_sigma_m = 1;      // while fixes continue at the surface
  double gps_wander_tau_s = 30;
};

class NavigationError {
 public:
  explicit NavigationError(const NavigationErrorParams& params);

  // A new dive: fresh scale and heading errors, the error so far kept.
  void start_dive(TrackNoise& noise);
  // Submerged: grows by the vehicle's velocity over ground (m/s) and the
  // caller's extra velocity error, over dt_s.
  void dead_reckon(TrackNoise& noise, std::array<double, 2> velocity, std::array<double, 2> extra, double dt_s);
  // The first GPS fix at the surface, then one per step while at the surface.
  void first_gps_fix(TrackNoise& noise);
  void gps_fix(TrackNoise& noise, double dt_s);

  std::array<double, 2> error() const { return error_; }

 private:
  NavigationErrorParams params_;
  std::array<double, 2> error_{};
  double scale_ = 0, heading_bias_ = 0;
  GaussMarkov random_east_, random_north_, gps_east_, gps_north_;
};

}  // namespace acomms::eval
