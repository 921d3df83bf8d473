#pragma once
// The Kalman-filter observer (Schneider 2013, eq. 3.9-3.23): per axis a
// constant-acceleration state [position, velocity, acceleration] driven by a
// Wiener-sequence jerk (Q = sigma_j^2 G G^T, G = [tau^2/2, tau, 1]^T),
// measuring position with noise R.
//
// The axes are independent and share A, Q, R and the initial covariance, so
// they share one covariance P as well: the state is one 3x3 matrix whose
// column i is axis i. Units are precision steps (and seconds), so a sample
// is an integer measurement and P(0,0) is the Gaussian model's variance.
//
// After a full transmission (the thesis leaves this open): position = the
// full's, velocity = acceleration = 0, P = diag(R, (2 m/s)^2, (0.1 m/s^2)^2):
// the position as good as one measurement, any speed an AUV or glider makes,
// little acceleration. P never depends on the data, only on the number of
// samples since the re-anchoring full, so both ends' tables follow it
// exactly. A full that a delta could have carried is an ordinary update.

#include <Eigen/Core>

#include "telemetry/observer.h"

namespace acomms::telemetry {

class KalmanObserver final : public Observer {
 public:
  explicit KalmanObserver(const TelemetryConfig& config);

  void reset(const GridPosition& position) override;
  Prediction predict() override;
  void update(const GridPosition& position) override;
  // x and P (9 + 9 doubles, by their bits).
  std::string save() const override;
  bool load(std::string_view bytes) override;

  // For tests: the posterior covariance after the last update (or reset).
  const Eigen::Matrix3d& covariance() const { return p_; }

 private:
  Eigen::Matrix3d a_;  // transition
  Eigen::Matrix3d q_;  // process noise
  double r_;           // measurement noise, precision steps squared
  Eigen::Matrix3d p0_;
  Eigen::Matrix3d x_;  // posterior state, column per axis
  Eigen::Matrix3d p_;  // posterior covariance
  Eigen::Matrix3d x_prior_;
  Eigen::Matrix3d p_prior_;
  bool has_prior_ = false;
};

}  // namespace acomms::telemetry
