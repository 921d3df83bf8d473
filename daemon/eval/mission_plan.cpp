#include "eval/mission_plan.h"

#include <cmath>

namespace acomms::eval {

MissionPlan::MissionPlan(double leg_min_m, double leg_max_m, double box_m, TrackNoise& noise)
    : leg_min_(leg_min_m), leg_max_(leg_max_m), box_(box_m), heading_(noise.uniform(-kTrackPi, kTrackPi)) {
  next(noise);
}

void MissionPlan::next(TrackNoise& noise) {
  const double pick = noise.uniform(0, 1);
  double turn;
  if (pick < 0.35) {
    turn = kTrackPi;  // survey line reversal
  } else if (pick < 0.7) {
    turn = noise.uniform(0, 1) < 0.5 ? kTrackPi / 2 : -kTrackPi / 2;
  } else {
    turn = noise.uniform(-kTrackPi, kTrackPi);
  }
  heading_ = wrap_pi(heading_ + turn);
  const double length = noise.uniform(leg_min_, leg_max_);
  std::array<double, 2> next{waypoint_[0] + length * track_cos(heading_), waypoint_[1] + length * track_sin(heading_)};
  if (std::fabs(next[0]) > box_ || std::fabs(next[1]) > box_) {
    heading_ = track_atan2(-waypoint_[1], -waypoint_[0]);
    next = {waypoint_[0] + length * track_cos(heading_), waypoint_[1] + length * track_sin(heading_)};
  }
  waypoint_ = next;
}

}  // namespace acomms::eval
