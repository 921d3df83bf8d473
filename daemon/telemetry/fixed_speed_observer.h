#pragma once
// The fixed-speed observer (Schneider 2013, eq. 3.5-3.7): the vehicle keeps
// its last heading at the configured speed, and keeps its last vertical
// change.
//
// Heading comes from the last two samples. The thesis writes it as an angle
// (atan2, then cos and sin); here the unit vector is taken directly,
// (dx, dy) / sqrt(dx^2 + dy^2), because sqrt is correctly rounded and the
// trigonometric functions are not, and the two ends must agree to the bit.
// Depth continues the last vertical change, z[n-1] + (z[n-1] - z[n-2]) (the
// thesis's printed dz is a typo, see the spec). With fewer than two samples
// since the full, or no horizontal motion between the last two, the
// horizontal prediction is the last position. Variance for the Gaussian
// model: (s tau)^2 on every axis (eq. 3.26).

#include <vector>

#include "telemetry/observer.h"

namespace acomms::telemetry {

class FixedSpeedObserver final : public Observer {
 public:
  explicit FixedSpeedObserver(const TelemetryConfig& config);

  void reset(const GridPosition& position) override;
  Prediction predict() override;
  void update(const GridPosition& position) override;
  std::string save() const override;
  bool load(std::string_view bytes) override;

 private:
  double step_;  // s * tau, in precision steps
  GridPosition last_{};
  GridPosition before_last_{};
  int known_ = 0;  // samples since the reset, up to 2
};

}  // namespace acomms::telemetry
