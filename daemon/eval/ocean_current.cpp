#include "eval/ocean_current.h"

namespace acomms::eval {

OceanCurrent::OceanCurrent(const OceanCurrentParams& params, TrackNoise& noise)
    : params_(params),
      axis_rad_(noise.uniform(-kTrackPi, kTrackPi)),
      phase_rad_(noise.uniform(-kTrackPi, kTrackPi)),
      east_{params.residual_sigma_mps, params.residual_tau_s},
      north_{params.residual_sigma_mps, params.residual_tau_s} {
  // Start the residual in its stationary distribution, not at zero.
  east_.value = params.residual_sigma_mps * noise.normal();
  north_.value = params.residual_sigma_mps * noise.normal();
}

std::array<double, 2> OceanCurrent::step(TrackNoise& noise, double t_s, double dt_s) {
  const double phase = 2 * kTrackPi * t_s / kM2PeriodS + phase_rad_;
  const double major = params_.tidal_major_mps * track_cos(phase);
  const double minor = params_.tidal_major_mps * params_.tidal_minor_ratio * track_sin(phase);
  const double c = track_cos(axis_rad_), s = track_sin(axis_rad_);
  return {major * c - minor * s + east_.step(noise, dt_s), major * s + minor * c + north_.step(noise, dt_s)};
}

}  // namespace acomms::eval
