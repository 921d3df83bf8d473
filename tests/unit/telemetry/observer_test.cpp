// The observers (Schneider 2013 eq. 3.5-3.23): what each predicts, on grid
// positions, and the Kalman filter's covariance.

#include <gtest/gtest.h>

#include <cmath>

#include "telemetry/fixed_speed_observer.h"
#include "telemetry/kalman_observer.h"

namespace acomms::telemetry {
namespace {

TEST(FixedSpeedObserver, PredictsTheLastPositionUntilItHasTwoSamples) {
  TelemetryConfig config;  // 1.5 m/s, 10 s, 1 m
  FixedSpeedObserver observer(config);
  observer.reset({100, 200, -30});
  const Prediction p = observer.predict();
  EXPECT_EQ(p.position, (GridPosition{100, 200, -30}));
  EXPECT_DOUBLE_EQ(p.variance[0], 225);  // (s tau)^2
  EXPECT_DOUBLE_EQ(p.variance[2], 225);
}

TEST(FixedSpeedObserver, KeepsHeadingAtTheConfiguredSpeedAndTheLastVerticalChange) {
  TelemetryConfig config;
  FixedSpeedObserver observer(config);
  observer.reset({0, 0, -10});
  observer.update({3, 4, -14});  // heading (0.6, 0.8), 4 m down
  const Prediction p = observer.predict();
  EXPECT_EQ(p.position, (GridPosition{3 + 9, 4 + 12, -18}));  // 15 m along the heading
}

TEST(FixedSpeedObserver, HoldsPositionWhenTheLastTwoSamplesDidNotMove) {
  TelemetryConfig config;
  FixedSpeedObserver observer(config);
  observer.reset({5, 5, 0});
  observer.update({5, 5, 0});
  EXPECT_EQ(observer.predict().position, (GridPosition{5, 5, 0}));
}

TEST(FixedSpeedObserver, WorksInPrecisionSteps) {
  TelemetryConfig config;
  config.precision_m = 0.5;  // 15 m = 30 steps
  FixedSpeedObserver observer(config);
  observer.reset({0, 0, 0});
  observer.update({-10, 0, 0});
  EXPECT_EQ(observer.predict().position, (GridPosition{-40, 0, 0}));
}

TEST(KalmanObserver, FirstPriorIsTheFullsPositionWithTheInitialCovariancePropagated) {
  TelemetryConfig config;
  KalmanObserver observer(config);
  observer.reset({10, -20, -5});
  const Prediction p = observer.predict();
  EXPECT_EQ(p.position, (GridPosition{10, -20, -5}));
  // (A P0 A^T + Q)(0,0) with P0 = diag(25, 4, 0.01), tau = 10:
  // 25 + 100 * 4 + 50^2 * 0.01 + 1e-3 * 50^2 = 452.5
  EXPECT_NEAR(p.variance[0], 452.5, 1e-9);
  EXPECT_DOUBLE_EQ(p.variance[0], p.variance[1]);
}

TEST(KalmanObserver, LearnsAConstantVelocity) {
  TelemetryConfig config;
  KalmanObserver observer(config);
  observer.reset({0, 0, 0});
  // 1.5 m/s east, 0.2 m/s down: after a while the prediction is on track.
  for (int n = 1; n <= 40; ++n) {
    observer.predict();
    observer.update({15 * n, 0, -2 * n});
  }
  const Prediction p = observer.predict();
  EXPECT_NEAR(static_cast<double>(p.position[0]), 15 * 41, 1);
  EXPECT_NEAR(static_cast<double>(p.position[2]), -2 * 41, 1);
  EXPECT_EQ(p.position[1], 0);
}

TEST(KalmanObserver, CovarianceDependsOnlyOnTheNumberOfSamples) {
  TelemetryConfig config;
  KalmanObserver a(config), b(config);
  a.reset({0, 0, 0});
  b.reset({1000, -7, -300});
  for (int n = 1; n <= 20; ++n) {
    const Prediction pa = a.predict(), pb = b.predict();
    EXPECT_EQ(pa.variance, pb.variance) << n;
    a.update({n, 2 * n, 0});
    b.update({1000 - 30 * n * n, -7, -300 + n});
  }
  // and settles: the prior variance converges to the Riccati fixed point
  for (int n = 0; n < 200; ++n) {
    a.predict();
    a.update({0, 0, 0});
  }
  const double v1 = a.predict().variance[0];
  a.update({0, 0, 0});
  const double v2 = a.predict().variance[0];
  EXPECT_NEAR(v1, v2, 1e-9 * v1);
  EXPECT_GT(v1, 0);
  EXPECT_LT(v1, 452.5);
}

}  // namespace
}  // namespace acomms::telemetry
