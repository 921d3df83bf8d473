// The forecast strategy of the depth objective (gram/depth_forecast.h) on
// constructed fields: a ridge it stays on, a shadow zone it does not cross,
// the earliest near-best reachable point (least pitch within its column);
// and the field built from a TL grid (gram/depth_forecast_field.h): the leg's
// end and the cap on columns.
#include "gram/depth_forecast.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>

#include "gram/depth_forecast_field.h"

namespace acomms::gram {
namespace {

// Depths 0..1000 m every 50 m; a column every 120 s up to `columns`; the
// same value steers and marks the shadow unless `raw` is given.
using Value = std::function<double(std::size_t k, double z)>;
ForecastField field(std::size_t columns, const Value& steer, const Value& raw = nullptr) {
  ForecastField f;
  for (int j = 0; j <= 20; ++j) f.depth_m.push_back(50.0 * j);
  for (std::size_t k = 0; k < columns; ++k) {
    f.time_s.push_back(120.0 * k);
    std::vector<double> s, r;
    for (double z : f.depth_m) {
      s.push_back(steer(k, z));
      r.push_back(raw ? raw(k, z) : steer(k, z));
    }
    f.steer.push_back(s);
    f.raw.push_back(r);
    f.allowed.emplace_back(f.depth_m.size(), true);
  }
  return f;
}

double bump(double z, double centre, double height, double width = 60) {
  return height * std::exp(-std::pow((z - centre) / width, 2));
}

// w = 0.75 m/s: 90 m per 120 s column.
const ForecastOptions kOptions{};

TEST(GramDepthForecast, ItStaysOnTheRidgeItIsOnEvenWithABetterPeakOutOfReach) {
  // A ridge at 500 m sinking 40 m a column (within reach), value 0.6; a
  // peak of 0.9 at 100 m, 400 m away: out of reach in 4 columns (270 m).
  const ForecastField f = field(4, [](std::size_t k, double z) {
    return std::max(bump(z, 500 + 40.0 * k, 0.6), bump(z, 100, 0.9));
  });
  const ForecastDecision d = forecast_depth(f, 500, kOptions);
  ASSERT_EQ(d.choice, ForecastChoice::kRidge);
  ASSERT_EQ(d.ridge_depth_m.size(), 4u);
  EXPECT_EQ(d.ridge_depth_m[0], 500);
  EXPECT_EQ(d.target_depth_m, 550);  // the ridge's grid peak at 540 m in column 1
  EXPECT_EQ(d.ridge_depth_m[3], 600);
  EXPECT_DOUBLE_EQ(d.target_time_s, 120);
  EXPECT_NEAR(d.depth_after(500, 60), 525, 1e-9);
  EXPECT_NEAR(d.depth_after(500, 360), 600, 1e-9);
  // Over 11 columns the same ridge is followed to 900 m while nothing
  // better is in reach, but the 0.9 peak comes in reach by column 5: a ridge
  // that is no longer high is left for it.
  const ForecastField g = field(11, [](std::size_t k, double z) {
    return std::max(bump(z, 500 + 40.0 * k, 0.6), bump(z, 100, 0.9));
  });
  const ForecastDecision e = forecast_depth(g, 500, kOptions);
  EXPECT_EQ(e.choice, ForecastChoice::kOptimum);
  EXPECT_EQ(e.target_depth_m, 100);
  const ForecastField alone = field(11, [](std::size_t k, double z) { return bump(z, 500 + 40.0 * k, 0.6); });
  const ForecastDecision a = forecast_depth(alone, 500, kOptions);
  ASSERT_EQ(a.choice, ForecastChoice::kRidge);
  EXPECT_EQ(a.ridge_depth_m[10], 900);
  EXPECT_NEAR(a.depth_after(500, 1200), 900, 1e-9);
}

TEST(GramDepthForecast, ARidgeThatEndsWithinTheHorizonIsLeftForTheReachableOptimum) {
  // The same ridge fades out after column 5: not followed.
  const ForecastField f = field(11, [](std::size_t k, double z) {
    return std::max(k <= 5 ? bump(z, 500 + 40.0 * k, 0.6) : 0.0, bump(z, 100, 0.9));
  });
  const ForecastDecision d = forecast_depth(f, 500, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kOptimum);
  EXPECT_EQ(d.target_depth_m, 100);
  EXPECT_NEAR(d.target_objective, 0.9, 1e-12);
  // 400 m away: the earliest column that reaches it (90 m a column: the
  // fifth, 600 s), not the horizon's end at the least pitch.
  EXPECT_DOUBLE_EQ(d.target_time_s, 600);
  EXPECT_NEAR(d.vertical_rate_mps, 400.0 / 600, 1e-12);
}

TEST(GramDepthForecast, AVehicleOffTheRidgeIsNotOnIt) {
  // 150 m above the ridge's peak its own objective is far below the peak's.
  const ForecastField f = field(11, [](std::size_t k, double z) { return bump(z, 500 + 40.0 * k, 0.6) + 0.01; });
  const ForecastDecision d = forecast_depth(f, 350, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kOptimum);
}

TEST(GramDepthForecast, ItDoesNotCrossAShadowZoneToABetterOptimum) {
  // Lit everywhere but a shadow zone from 150 to 250 m (raw objective 0):
  // the best (0.9 at 100 m) lies beyond it; 0.6 at 600 m does not.
  auto steer = [](std::size_t, double z) { return std::max({bump(z, 100, 0.9), bump(z, 600, 0.6), 0.05}); };
  auto raw = [&](std::size_t k, double z) { return z >= 150 && z <= 250 ? 0.0 : steer(k, z); };
  const ForecastDecision d = forecast_depth(field(11, steer, raw), 300, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kOptimum);
  EXPECT_EQ(d.target_depth_m, 600);
  // Without the shadow zone it goes for the better one.
  const ForecastDecision open = forecast_depth(field(11, steer), 300, kOptions);
  EXPECT_EQ(open.target_depth_m, 100);
}

TEST(GramDepthForecast, AVehicleStartingInAShadowMayLeaveIt) {
  // Near the surface in a shadow (0 above 200 m), lit below.
  auto steer = [](std::size_t, double z) { return z < 200 ? 0.0 : bump(z, 400, 0.8) + 0.1; };
  const ForecastDecision d = forecast_depth(field(11, steer), 20, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kOptimum);
  EXPECT_EQ(d.target_depth_m, 400);
}

TEST(GramDepthForecast, TheOptimumItCanReachWins) {
  // 1.0 at 900 m is 800 m away: unreachable in 10 columns (900 m at most
  // by the last, but it is only there in column 2). 0.7 at 250 m is.
  const ForecastField f = field(11, [](std::size_t k, double z) {
    return std::max(k == 2 ? bump(z, 900, 1.0) : 0.0, bump(z, 250, 0.7)) + 0.01;
  });
  const ForecastDecision d = forecast_depth(f, 100, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kOptimum);
  EXPECT_EQ(d.target_depth_m, 250);
  // With a vertical speed that reaches it in 240 s it goes for 900 m.
  ForecastOptions fast = kOptions;
  fast.vertical_speed_mps = 4;
  const ForecastDecision f4 = forecast_depth(f, 100, fast);
  EXPECT_EQ(f4.target_depth_m, 900);
  EXPECT_DOUBLE_EQ(f4.target_time_s, 240);
}

TEST(GramDepthForecast, OfNearBestPointsTheEarliestNotTheLatest) {
  // 0.8 at 300 m in column 3 and 0.82 at 700 m in column 10; from 500 m the
  // second needs 200 m in 1200 s (the least pitch), the first 200 m in 360 s.
  // Both are within 10% of the best: the earliest is the target.
  const ForecastField f = field(11, [](std::size_t k, double z) {
    return (k == 3 ? bump(z, 300, 0.8) : 0.0) + (k == 10 ? bump(z, 700, 0.82) : 0.0) + 0.02;
  });
  const ForecastDecision d = forecast_depth(f, 500, kOptions);
  EXPECT_EQ(d.target_depth_m, 300);
  EXPECT_DOUBLE_EQ(d.target_time_s, 360);
  EXPECT_NEAR(d.depth_after(500, 180), 400, 1e-9);  // half way on the straight path
  // With the strict optimum (tolerance 0) the better, later one.
  ForecastOptions strict = kOptions;
  strict.optimum_tolerance = 0;
  const ForecastDecision s = forecast_depth(f, 500, strict);
  EXPECT_EQ(s.target_depth_m, 700);
  EXPECT_DOUBLE_EQ(s.target_time_s, 1200);
  // The tolerance is relative: 0.7 is not within 10% of 0.82.
  const ForecastField g = field(11, [](std::size_t k, double z) {
    return (k == 3 ? bump(z, 300, 0.7) : 0.0) + (k == 10 ? bump(z, 700, 0.82) : 0.0) + 0.02;
  });
  EXPECT_EQ(forecast_depth(g, 500, kOptions).target_depth_m, 700);
}

TEST(GramDepthForecast, InTheEarliestColumnTheLeastPitch) {
  // Two equal peaks in column 4 only, at 250 m and 800 m: from 450 m the
  // nearer (200 m against 350 m) is the target.
  const ForecastField f = field(11, [](std::size_t k, double z) {
    return (k == 4 ? std::max(bump(z, 250, 0.9), bump(z, 800, 0.9)) : 0.0) + 0.02;
  });
  const ForecastDecision d = forecast_depth(f, 450, kOptions);
  EXPECT_EQ(d.target_depth_m, 250);
  EXPECT_DOUBLE_EQ(d.target_time_s, 480);
}

TEST(GramDepthForecast, ForbiddenDepthsAreNeitherTargetsNorPassages) {
  // The best is below the allowed depths (max 600 m): it takes the best allowed.
  ForecastField f = field(11, [](std::size_t, double z) { return std::max(bump(z, 900, 1.0), bump(z, 400, 0.5)); });
  for (auto& column : f.allowed)
    for (std::size_t j = 0; j < column.size(); ++j) column[j] = f.depth_m[j] <= 600;
  const ForecastDecision d = forecast_depth(f, 350, kOptions);
  EXPECT_LE(d.target_depth_m, 600);
  EXPECT_EQ(d.target_depth_m, 400);
}

TEST(GramDepthForecast, NothingAheadReceivesItHolds) {
  const ForecastDecision d = forecast_depth(field(11, [](std::size_t, double) { return 0.0; }), 230, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kHold);
  EXPECT_EQ(d.target_depth_m, 230);
  EXPECT_EQ(d.depth_after(230, 1000), 230);
  EXPECT_STREQ(forecast_choice_name(d.choice), "hold");
}

TEST(GramDepthForecast, BadFieldsAndOptionsAreRefusedByName) {
  ForecastField f = field(3, [](std::size_t, double) { return 0.5; });
  ForecastOptions o = kOptions;
  o.vertical_speed_mps = 0;
  EXPECT_THROW(forecast_depth(f, 10, o), std::invalid_argument);
  f.time_s[1] = 0;
  try {
    forecast_depth(f, 10, kOptions);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "the forecast field's times must be strictly increasing");
  }
  ForecastField g = field(3, [](std::size_t, double) { return 0.5; });
  g.steer[2].pop_back();
  EXPECT_THROW(forecast_depth(g, 10, kOptions), std::invalid_argument);
  DepthForecastRequest r;
  r.forecast_horizon_s = 60;
  EXPECT_EQ(*validate_depth_forecast_request(r, 120),
            "forecast_horizon_s = 60 must be at least horizon_s = 120 (one forecast column every horizon_s)");
  // A query may not ask for more than 120 columns (1000 would hold the
  // model service for minutes).
  r.forecast_horizon_s = 120 * 120;
  EXPECT_FALSE(validate_depth_forecast_request(r, 120));
  r.forecast_horizon_s = 121 * 120;
  EXPECT_EQ(*validate_depth_forecast_request(r, 120),
            "forecast_horizon_s = 14520 must be at most 120 times horizon_s = 120 (one forecast column every horizon_s)");
  r.forecast_horizon_s = 3600;
  r.leg_end_range_m = -1;
  EXPECT_EQ(*validate_depth_forecast_request(r, 120), "leg_end_range_m must be finite and at least 0");
}

// The field from a TL grid: a layer of low loss at 300 m from 2 km on,
// nothing before (shadow); the vehicle at 1 km, 1.5 m/s out, 120 s windows.
TransmissionLoss layered_from_2km() {
  TransmissionLoss tl;
  for (int i = 0; i <= 60; ++i) tl.range_m.push_back(100.0 * i);  // 0..6 km
  for (int j = 0; j <= 20; ++j) tl.depth_m.push_back(25.0 * j);   // 0..500 m
  for (double z : tl.depth_m)
    for (double r : tl.range_m)
      tl.tl_db.push_back(r >= 2000 && std::abs(z - 300) <= 25 ? 70.0 : INFINITY);
  return tl;
}

TEST(GramDepthForecastField, ColumnsAreTheWindowsAheadAndTheVehicleHeadsForTheLayer) {
  Environment env;
  for (auto [z, c] : {std::pair{0.0, 1500.0}, {500.0, 1500.0}}) {
    auto* p = env.add_sound_speed();
    p->set_depth_m(z);
    p->set_speed_mps(c);
  }
  const std::vector<TransmissionLoss> tl{layered_from_2km()};
  DepthObjectiveRequest q;
  q.range_m = 1000;
  q.speed_mps = 1.5;
  q.horizon_s = 120;
  q.h_max_db = 100;
  q.limits = {5, 480, 10};
  q.forecast = DepthForecastRequest{};
  q.forecast->forecast_horizon_s = 1200;
  q.forecast->current_depth_m = 50;
  q.forecast->options.optimum_tolerance = 0;  // the strict optimum (the layer's values differ by less than 0.02)
  const DepthObjectiveResult r = compute_depth_objective(tl, env, q);
  EXPECT_FALSE(r.best.any_signal);  // the next window (1000-1180 m) is all shadow
  ASSERT_TRUE(r.forecast);
  const DepthForecastResult& f = *r.forecast;
  ASSERT_EQ(f.field.time_s.size(), 11u);
  EXPECT_DOUBLE_EQ(f.windows[10].begin_m, 1000 + 1.5 * 1200);
  EXPECT_DOUBLE_EQ(f.horizon_used_s, 1200);
  // Column 4 ([1720, 1900) m) is dark; from column 6 ([2080, 2260) m) the
  // layer is lit over the whole window.
  EXPECT_EQ(f.field.raw[4][12], 0);
  EXPECT_NEAR(f.field.raw[6][12], 0.3, 1e-12);
  EXPECT_EQ(f.decision.choice, ForecastChoice::kOptimum);
  // The caustic bias: the steering objective (1/50 m low-pass from the
  // surface) peaks below the raw layer's 275-325 m.
  EXPECT_GT(f.decision.target_depth_m, 300);
  EXPECT_LE(std::abs(f.decision.target_depth_m - 50), 0.75 * f.decision.target_time_s);
  EXPECT_NEAR(f.next_depth_m, f.decision.depth_after(50, 120), 1e-9);

  // Past the grid's last range the forecast stops.
  q.range_m = 5500;
  const DepthObjectiveResult end = compute_depth_objective(tl, env, q);
  EXPECT_EQ(end.forecast->field.time_s.size(), 3u);  // 5500, 5680, 5860; 6040 is off the grid

  // A leg that ends (the vehicle turns) at 1400 m: the columns stop there,
  // but the next window is kept: 1000, 1180 (1360 is within; 1540 is past).
  q.range_m = 1000;
  q.forecast->leg_end_range_m = 1400;
  const DepthObjectiveResult leg = compute_depth_objective(tl, env, q);
  EXPECT_EQ(leg.forecast->field.time_s.size(), 3u);
  EXPECT_DOUBLE_EQ(leg.forecast->horizon_used_s, 240);
  q.forecast->leg_end_range_m = 1000;  // turning now: the next window only
  EXPECT_EQ(compute_depth_objective(tl, env, q).forecast->field.time_s.size(), 2u);
  // Coming back (heading 180) the leg ends at a smaller range.
  q.heading_deg = 180;
  q.range_m = 1800;
  q.forecast->leg_end_range_m = 1500;
  EXPECT_EQ(compute_depth_objective(tl, env, q).forecast->field.time_s.size(), 2u);  // 1800, 1620; 1440 is past
}

}  // namespace
}  // namespace acomms::gram
