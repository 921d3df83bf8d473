// The forecast planner (gram/depth_forecast.h) at its edges: a client's
// depth far outside the field and a single-depth field (the plan's grid is
// the field's, whatever the depth reported), vertical speeds at the ends of
// what is accepted, limits that fall between the field's depths, and a
// vehicle outside its allowed depths by more than a window's reach (it
// heads back instead of holding where it must not be).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "gram/depth_forecast.h"

namespace acomms::gram {
namespace {

// Depths 0..1000 m every 50 m; a column every 120 s; `allowed` decides the
// limits per column (all allowed when null).
using Value = std::function<double(std::size_t k, double z)>;
using Allowed = std::function<bool(std::size_t k, double z)>;
ForecastField field(std::size_t columns, const Value& value, const Allowed& allowed = nullptr) {
  ForecastField f;
  for (int j = 0; j <= 20; ++j) f.depth_m.push_back(50.0 * j);
  for (std::size_t k = 0; k < columns; ++k) {
    f.time_s.push_back(120.0 * k);
    std::vector<double> v;
    std::vector<bool> a;
    for (double z : f.depth_m) {
      v.push_back(value(k, z));
      a.push_back(!allowed || allowed(k, z));
    }
    f.steer.push_back(v);
    f.raw.push_back(v);
    f.allowed.push_back(a);
  }
  return f;
}

double bump(double z, double centre, double height, double width = 60) {
  return height * std::exp(-std::pow((z - centre) / width, 2));
}

const ForecastOptions kOptions{};  // 0.75 m/s: 90 m per 120 s window

TEST(GramDepthForecastLimits, ADepthReportedFarBelowTheFieldIsPlannedFromItsBottom) {
  // The field ends at 1000 m; a client reports 100 km. The plan's grid is
  // the field's (it was the span from the field's top to the vehicle: 10^4
  // depths here, 10^7 at 10^8 m), so the plan starts at the field's bottom
  // and climbs to the layer at 600 m.
  const ForecastField f = field(11, [](std::size_t, double z) { return bump(z, 600, 0.8) + 0.01; });
  const ForecastDecision d = forecast_depth(f, 1e5, kOptions);
  ASSERT_EQ(d.path_depth_m.size(), 11u);
  EXPECT_EQ(d.path_depth_m[0], 1e5);  // the vehicle's, as reported
  EXPECT_NE(d.choice, ForecastChoice::kHold);
  EXPECT_NEAR(d.path_depth_m[1], 1000 - 90, 1e-6);
  EXPECT_NEAR(d.target_depth_m, 600, 10);
  // 10^8 m: no grid of 10^7 depths, the same plan.
  const ForecastDecision far = forecast_depth(f, 1e8, kOptions);
  EXPECT_EQ(std::vector<double>(far.path_depth_m.begin() + 1, far.path_depth_m.end()),
            std::vector<double>(d.path_depth_m.begin() + 1, d.path_depth_m.end()));
}

TEST(GramDepthForecastLimits, ASingleDepthFieldIsOneDepthWhateverTheVehiclesDepth) {
  // One depth: no span, so no cap from the span either; the grid is that
  // one depth (it was 10^5 depths from 500 m to a vehicle at 10^6 m).
  ForecastField f;
  f.depth_m = {500};
  for (int k = 0; k < 4; ++k) {
    f.time_s.push_back(120.0 * k);
    f.steer.push_back({0.5});
    f.raw.push_back({0.5});
    f.allowed.push_back({true});
  }
  const ForecastDecision d = forecast_depth(f, 1e6, kOptions);
  ASSERT_EQ(d.path_depth_m.size(), 4u);
  for (std::size_t k = 1; k < 4; ++k) EXPECT_EQ(d.path_depth_m[k], 500) << k;
  EXPECT_NEAR(d.expected_score, 0.5, 1e-12);
}

TEST(GramDepthForecastLimits, VerticalSpeedsBeyondAnyVehicleAreRefusedAndTinyOnesHold) {
  ForecastOptions o = kOptions;
  o.vertical_speed_mps = 11;
  EXPECT_EQ(*validate_forecast_options(o), "vertical_speed_mps = 11 must be at most 10 m/s");
  o.vertical_speed_mps = 1e300;  // w·Δt / step overflowed a long before the clamp
  EXPECT_THROW(forecast_depth(field(3, [](std::size_t, double) { return 0.5; }), 10, o), std::invalid_argument);
  o.vertical_speed_mps = 10;
  EXPECT_FALSE(validate_forecast_options(o));
  // 10^-300 m/s: the default terminal (the field's span / w) and its
  // column count are far past any integer; clamped first, it cannot move.
  o.vertical_speed_mps = 1e-300;
  const ForecastDecision d = forecast_depth(field(11, [](std::size_t, double z) { return bump(z, 900, 0.9) + 0.1; }), 500, o);
  for (double z : d.path_depth_m) EXPECT_EQ(z, 500);
  // Non-finite field depths are refused, not planned over.
  ForecastField bad = field(3, [](std::size_t, double) { return 0.5; });
  bad.depth_m.back() = INFINITY;
  EXPECT_EQ(*validate_forecast_field(bad), "the forecast field's depths must be finite");
}

TEST(GramDepthForecastLimits, ALimitBetweenTheFieldsDepthsIsNotPassed) {
  // The limit at 810 m, the field every 50 m: 800 m allowed, 850 m not.
  // The best is deeper (1000 m); a plan depth of 820 m is nearest 800 m
  // but past the limit (bottom clearance): the plan stays at or above it.
  const ForecastField f = field(11, [](std::size_t, double z) { return bump(z, 1000, 1.0, 200); },
                                [](std::size_t, double z) { return z <= 810; });
  const ForecastDecision d = forecast_depth(f, 500, kOptions);
  for (double z : d.path_depth_m) EXPECT_LE(z, 810);
  EXPECT_GE(d.path_depth_m.back(), 750);  // it goes as deep as it may
  // The same from above: a minimum of 140 m (field depths 100 and 150 m).
  const ForecastField g = field(11, [](std::size_t, double z) { return bump(z, 0, 1.0, 200); },
                                [](std::size_t, double z) { return z >= 140; });
  const ForecastDecision e = forecast_depth(g, 500, kOptions);
  for (double z : e.path_depth_m) EXPECT_GE(z, 140);
  EXPECT_LE(e.path_depth_m.back(), 200);
}

TEST(GramDepthForecastLimits, AVehicleDeeperThanItsLimitByMoreThanAReachHeadsBack) {
  // Max 600 m, the vehicle reports 900 m (three windows' reach below) and
  // nothing is predicted to receive: it climbs at full speed, not holds.
  const ForecastField f = field(11, [](std::size_t, double) { return 0.0; },
                                [](std::size_t, double z) { return z <= 600; });
  const ForecastDecision d = forecast_depth(f, 900, kOptions);
  EXPECT_NE(d.choice, ForecastChoice::kHold);
  ASSERT_EQ(d.path_depth_m.size(), 11u);
  EXPECT_NEAR(d.path_depth_m[1], 810, 1e-6);
  EXPECT_NEAR(d.path_depth_m[2], 720, 1e-6);
  EXPECT_NEAR(d.path_depth_m[3], 630, 1e-6);
  for (std::size_t k = 4; k < 11; ++k) EXPECT_LE(d.path_depth_m[k], 600) << k;
  EXPECT_NEAR(d.depth_after(900, 120), 810, 1e-6);
  EXPECT_EQ(d.target_time_s, 480);  // the target: back inside
  EXPECT_EQ(d.target_objective, 0);
  EXPECT_EQ(d.expected_score, 0);
}

TEST(GramDepthForecastLimits, WhenTheBottomShoalsFasterThanItCanClimbItClimbsAtFullSpeed) {
  // The deepest allowed depth rises 150 m a window (from 800 m to 200 m),
  // faster than the 90 m it can climb: from 700 m it falls outside from
  // the third window and climbs all the way, rejoining the band at 200 m.
  const auto deepest = [](std::size_t k) { return std::max(800.0 - 150.0 * static_cast<double>(k), 200.0); };
  const ForecastField f = field(11, [](std::size_t, double z) { return bump(z, 100, 0.6, 300); },
                                [&](std::size_t k, double z) { return z <= deepest(k); });
  const ForecastDecision d = forecast_depth(f, 700, kOptions);
  EXPECT_NE(d.choice, ForecastChoice::kHold);
  // 700, 610 (inside), 520, 430, 340, 250 (outside: 500, 350, 200, 200), 160 (inside again).
  for (std::size_t k = 1; k <= 6; ++k) EXPECT_NEAR(d.path_depth_m[k], 700 - 90.0 * static_cast<double>(k), 1e-6) << k;
  for (std::size_t k = 6; k < 11; ++k) EXPECT_LE(d.path_depth_m[k], deepest(k)) << k;
}

TEST(GramDepthForecastLimits, AForbiddenGapIsStillNotCrossedFromInsideTheAllowedDepths) {
  // The way back is only for a vehicle outside its allowed depths: one
  // inside does not cross a forbidden gap (600-700 m) to a better layer.
  const ForecastField f = field(11, [](std::size_t, double z) { return std::max(bump(z, 900, 1.0), 0.2); },
                                [](std::size_t, double z) { return z < 600 || z > 700; });
  const ForecastDecision d = forecast_depth(f, 500, kOptions);
  for (double z : d.path_depth_m) EXPECT_LT(z, 600);
}

}  // namespace
}  // namespace acomms::gram
