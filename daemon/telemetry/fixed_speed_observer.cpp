#include "telemetry/fixed_speed_observer.h"

#include <cmath>

#include "telemetry/deterministic_math.h"
#include "telemetry/state_bytes.h"

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

// known (1), then last and before_last (3 x 8 each).
std::string FixedSpeedObserver::save() const {
  StateWriter out;
  out.put(static_cast<uint64_t>(known_), 1);
  for (const GridPosition* p : {&last_, &before_last_})
    for (int64_t v : *p) out.put(static_cast<uint64_t>(v), 8);
  return out.take();
}

bool FixedSpeedObserver::load(std::string_view bytes) {
  StateReader in(bytes);
  uint64_t known = 0;
  GridPosition last{}, before_last{};
  if (!in.get(1, &known) || known > 2) return false;
  for (GridPosition* p : {&last, &before_last}) {
    for (int64_t& v : *p) {
      uint64_t raw = 0;
      if (!in.get(8, &raw)) return false;
      v = static_cast<int64_t>(raw);
    }
  }
  if (!in.done()) return false;
  known_ = static_cast<int>(known);
  last_ = last;
  before_last_ = before_last;
  return true;
}

}  // namespace acomms::telemetry
