#include "telemetry/observer.h"

#include "telemetry/fixed_speed_observer.h"
#include "telemetry/kalman_observer.h"

namespace acomms::telemetry {

std::unique_ptr<Observer> make_observer(const TelemetryConfig& config) {
  switch (config.observer) {
    case ObserverKind::kFixedSpeed:
      return std::make_unique<FixedSpeedObserver>(config);
    case ObserverKind::kKalman:
      return std::make_unique<KalmanObserver>(config);
  }
  return nullptr;
}

}  // namespace acomms::telemetry
