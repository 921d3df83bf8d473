#pragma once
// The orbital motion of surface waves that a shallow vehicle rides, as its
// navigation records it (realistic_track.h).
//
// Linear (Airy) deep-water wave theory: a wave of amplitude a and angular
// frequency w moves the water in circles of radius a e^(-k z) at depth z,
// with k = w^2 / g. A swell of 0.5-1.5 m amplitude and 7-11 s period (sea
// state 3-4) moves a vehicle at 10 m by a few decimetres, at 50 m by a few
// centimetres, at the surface by the full amplitude; sampled every 10 s
// (near the wave period) this is noise, not a motion an observer can
// follow. Two components (a swell and a shorter wind sea) with drawn
// heights, periods, directions and phases.
//
// Thread-safe after construction: displacement() is const.

#include <array>

#include "eval/track_math.h"

namespace acomms::eval {

class SurfaceWaves {
 public:
  explicit SurfaceWaves(TrackNoise& noise);
  // Displacement (east, north, down) in metres at time t_s and depth_m.
  std::array<double, 3> displacement(double t_s, double depth_m) const;

 private:
  struct Component {
    double amplitude_m, omega, k, direction_rad, phase_rad;
  };
  std::array<Component, 2> components_;
};

}  // namespace acomms::eval
