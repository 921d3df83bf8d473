#include "telemetry/fixed_speed_observer.h"

#include <cmath>

#include "telemetry/deterministic_math.h"

namespace acomms::telemetry {

FixedSpeedObserver::FixedSpeedObserver(const TelemetryConfig& config)
    : step_(config.speed_mps * config.tau_s / config.precision_m) {}

void FixedSpeedObserver::reset(const GridPosition& position) {
  last_ = position;
  known_ = 1;
}

Prediction FixedSpeedObserver::predict() {
  Prediction prediction;
  prediction.position = last_;
  prediction.variance.fill(step_ * step_);
  if (known_ < 2) return prediction;
  const double dx = static_cast<double>(last_[0] - before_last_[0]);
  const double dy = static_cast<double>(last_[1] - before_last_[1]);
  const double distance = std::sqrt(dx * dx + dy * dy);
  if (distance > 0) {
    prediction.position[0] = last_[0] + round_to_int(step_ * dx / distance);
    prediction.position[1] = last_[1] + round_to_int(step_ * dy / distance);
  }
  prediction.position[2] = last_[2] + (last_[2] - before_last_[2]);
  return prediction;
}

void FixedSpeedObserver::update(const GridPosition& position) {
  before_last_ = last_;
  last_ = position;
  if (known_ < 2) ++known_;
}

}  // namespace acomms::telemetry
