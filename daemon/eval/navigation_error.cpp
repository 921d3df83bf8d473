#include "eval/navigation_error.h"

namespace acomms::eval {

NavigationError::NavigationError(const NavigationErrorParams& params)
    : params_(params),
      random_east_{params.random_sigma_mps, params.random_tau_s},
      random_north_{params.random_sigma_mps, params.random_tau_s},
      gps_east_{params.gps_wander_sigma_m, params.gps_wander_tau_s},
      gps_north_{params.gps_wander_sigma_m, params.gps_wander_tau_s} {}

void NavigationError::start_dive(TrackNoise& noise) {
  scale_ = params_.scale_sigma * noise.normal();
  heading_bias_ = params_.heading_bias_sigma_rad * noise.normal();
}

void NavigationError::dead_reckon(TrackNoise& noise, std::array<double, 2> v, std::array<double, 2> extra,
                                  double dt_s) {
  // scale along the velocity, heading bias across it (small-angle rotation)
  const double ex = scale_ * v[0] - heading_bias_ * v[1] + random_east_.step(noise, dt_s) + extra[0];
  const double ey = scale_ * v[1] + heading_bias_ * v[0] + random_north_.step(noise, dt_s) + extra[1];
  error_[0] += ex * dt_s;
  error_[1] += ey * dt_s;
}

void NavigationError::first_gps_fix(TrackNoise& noise) {
  gps_east_.value = params_.gps_sigma_m * noise.normal();
  gps_north_.value = params_.gps_sigma_m * noise.normal();
  error_ = {gps_east_.value, gps_north_.value};
}

void NavigationError::gps_fix(TrackNoise& noise, double dt_s) {
  error_ = {gps_east_.step(noise, dt_s), gps_north_.step(noise, dt_s)};
}

}  // namespace acomms::eval
