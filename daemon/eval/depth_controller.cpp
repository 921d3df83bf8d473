#include "eval/depth_controller.h"

#include <algorithm>

#include "eval/track_math.h"

namespace acomms::eval {

DepthController::DepthController(double natural_period_s, double damping, double max_rate_mps)
    : omega_(2 * kTrackPi / natural_period_s), damping_(damping), max_rate_(max_rate_mps) {}

double DepthController::step(double command_m, double dt_s) {
  const double acceleration = omega_ * omega_ * (command_m - depth_) - 2 * damping_ * omega_ * rate_;
  rate_ = std::clamp(rate_ + acceleration * dt_s, -max_rate_, max_rate_);
  depth_ += rate_ * dt_s;
  if (depth_ < 0) {
    depth_ = 0;
    rate_ = std::max(rate_, 0.0);
  }
  return depth_;
}

}  // namespace acomms::eval
