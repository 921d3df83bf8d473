#pragma once
// The current a generated vehicle swims in (realistic_track.h): what sets a
// torpedo AUV off its track between waypoints and what a glider, three to
// five times slower, fights and mis-estimates for hours.
//
// Two parts, both horizontal and the same at every depth (a depth-averaged
// current, which is what a glider estimates):
// - a tide: the semidiurnal lunar constituent M2 (period 12.42 h) as a
//   current ellipse (major axis amplitude, minor/major ratio, orientation,
//   phase), the dominant tidal current on most shelves;
// - a slowly wandering residual (wind-driven and eddy flow): a first-order
//   Gauss-Markov process per axis with a correlation time of hours, so the
//   current a glider estimated at one surfacing is noticeably wrong by the
//   next.
// Magnitudes are the caller's (realistic_track.cpp says which and why).
//
// Not thread-safe: one track's state.

#include <array>

#include "eval/track_math.h"

namespace acomms::eval {

struct OceanCurrentParams {
  double tidal_major_mps = 0.2;
  double tidal_minor_ratio = 0.4;
  double residual_sigma_mps = 0.05;
  double residual_tau_s = 3 * 3600;
};

class OceanCurrent {
 public:
  // Orientation and phase of the tide are drawn from noise.
  OceanCurrent(const OceanCurrentParams& params, TrackNoise& noise);
  // The current (east, north) in m/s at time t_s, advancing the residual by dt_s.
  std::array<double, 2> step(TrackNoise& noise, double t_s, double dt_s);

 private:
  static constexpr double kM2PeriodS = 12.42 * 3600;
  OceanCurrentParams params_;
  double axis_rad_, phase_rad_;
  GaussMarkov east_, north_;
};

}  // namespace acomms::eval
