#pragma once
// The waypoints of a generated mission (realistic_track.h): legs of
// irregular length at irregular headings, so turns come at irregular times
// (a lawnmower's regular turns are the kindest case for an observer).
//
// Each leg turns from the previous one by a drawn angle: mostly survey-like
// (a reversal or a right angle, either way), sometimes any angle (a transit,
// a re-plan). Legs stay inside a square of +-box_m around the start, so any
// duration stays inside the telemetry region: a leg that would leave it is
// turned back towards the start.
//
// Not thread-safe: one track's state.

#include <array>

#include "eval/track_math.h"

namespace acomms::eval {

class MissionPlan {
 public:
  MissionPlan(double leg_min_m, double leg_max_m, double box_m, TrackNoise& noise);
  // The waypoint steered for; next() moves to the following one.
  const std::array<double, 2>& waypoint() const { return waypoint_; }
  void next(TrackNoise& noise);

 private:
  double leg_min_, leg_max_, box_;
  double heading_;
  std::array<double, 2> waypoint_{};
};

}  // namespace acomms::eval
