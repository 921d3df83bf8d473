#include "telemetry/kalman_observer.h"

#include <bit>
#include <cmath>

#include "telemetry/deterministic_math.h"
#include "telemetry/state_bytes.h"

namespace acomms::telemetry {

KalmanObserver::KalmanObserver(const TelemetryConfig& config) {
  const double tau = config.tau_s;
  const double p2 = config.precision_m * config.precision_m;
  a_ << 1, tau, tau * tau / 2,  //
      0, 1, tau,                //
      0, 0, 1;
  const Eigen::Vector3d g(tau * tau / 2, tau, 1);
  q_ = (config.sigma_j2 / p2) * (g * g.transpose());
  r_ = config.r_m2 / p2;
  p0_.setZero();
  p0_.diagonal() << r_, 4.0 / p2, 0.01 / p2;
  x_.setZero();
  p_ = p0_;
}

void KalmanObserver::reset(const GridPosition& position) {
  x_.setZero();
  for (int axis = 0; axis < kAxes; ++axis) x_(0, axis) = static_cast<double>(position[axis]);
  p_ = p0_;
  has_prior_ = false;
}

Prediction KalmanObserver::predict() {
  x_prior_ = a_ * x_;
  p_prior_ = a_ * p_ * a_.transpose() + q_;
  has_prior_ = true;
  Prediction prediction;
  for (int axis = 0; axis < kAxes; ++axis) {
    prediction.position[axis] = round_to_int(x_prior_(0, axis));
    prediction.variance[axis] = p_prior_(0, 0);
  }
  return prediction;
}

void KalmanObserver::update(const GridPosition& position) {
  if (!has_prior_) predict();
  has_prior_ = false;
  // H = [1 0 0]: S = P-(0,0) + R, K = P- H^T / S.
  const Eigen::Vector3d gain = p_prior_.col(0) / (p_prior_(0, 0) + r_);
  Eigen::RowVector3d innovation;
  for (int axis = 0; axis < kAxes; ++axis)
    innovation(axis) = static_cast<double>(position[axis]) - x_prior_(0, axis);
  x_ = x_prior_ + gain * innovation;
  p_ = p_prior_ - gain * p_prior_.row(0);
}

}  // namespace acomms::telemetry

namespace acomms::telemetry {

std::string KalmanObserver::save() const {
  StateWriter out;
  for (const Eigen::Matrix3d* m : {&x_, &p_})
    for (int i = 0; i < 9; ++i) out.put(std::bit_cast<uint64_t>(m->data()[i]), 8);
  return out.take();
}

bool KalmanObserver::load(std::string_view bytes) {
  StateReader in(bytes);
  Eigen::Matrix3d x, p;
  for (Eigen::Matrix3d* m : {&x, &p}) {
    for (int i = 0; i < 9; ++i) {
      uint64_t raw = 0;
      if (!in.get(8, &raw)) return false;
      m->data()[i] = std::bit_cast<double>(raw);
      if (!std::isfinite(m->data()[i])) return false;
    }
  }
  if (!in.done()) return false;
  x_ = x;
  p_ = p;
  has_prior_ = false;
  return true;
}

}  // namespace acomms::telemetry
