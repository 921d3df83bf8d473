#include "eval/surface_waves.h"

namespace acomms::eval {
namespace {

constexpr double kGravity = 9.81;

}  // namespace

SurfaceWaves::SurfaceWaves(TrackNoise& noise) {
  const double periods[2] = {noise.uniform(7, 11), noise.uniform(4, 6)};
  const double amplitudes[2] = {noise.uniform(0.5, 1.5), noise.uniform(0.2, 0.5)};
  for (int i = 0; i < 2; ++i) {
    const double omega = 2 * kTrackPi / periods[i];
    components_[i] = Component{amplitudes[i], omega, omega * omega / kGravity, noise.uniform(-kTrackPi, kTrackPi),
                               noise.uniform(-kTrackPi, kTrackPi)};
  }
}

std::array<double, 3> SurfaceWaves::displacement(double t_s, double depth_m) const {
  std::array<double, 3> out{};
  for (const Component& c : components_) {
    const double radius = c.amplitude_m * track_exp_neg(-c.k * depth_m);
    const double phase = c.omega * t_s + c.phase_rad;
    const double along = radius * track_cos(phase);
    out[0] += along * track_cos(c.direction_rad);
    out[1] += along * track_sin(c.direction_rad);
    out[2] += radius * track_sin(phase);
  }
  return out;
}

}  // namespace acomms::eval
