// The forecast strategy of the depth objective (gram/depth_forecast.h), a
// path planner, on constructed fields: a ridge it stays on while it stays
// the best, a shadow zone it goes round when a lit path exists, a curving
// band it follows, a band beyond the horizon that still draws it (the
// terminal value), the limits; and the field built from a TL grid
// (gram/depth_forecast_field.h): the bias towards depth, the reception
// score, the leg's end and the cap on columns.
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

// w = 0.75 m/s: 90 m per 120 s column; the plan looks past the last
// column as long as crossing the field's 1000 m takes (the default terminal).
const ForecastOptions kOptions{};

// Every planned depth is reachable from the previous one.
void expect_flyable(const ForecastDecision& d, const ForecastOptions& o) {
  ASSERT_EQ(d.path_depth_m.size(), d.path_time_s.size());
  for (std::size_t k = 1; k < d.path_depth_m.size(); ++k)
    EXPECT_LE(std::abs(d.path_depth_m[k] - d.path_depth_m[k - 1]),
              o.vertical_speed_mps * (d.path_time_s[k] - d.path_time_s[k - 1]) + 1e-9)
        << k;
}

TEST(GramDepthForecast, ItStaysOnTheRidgeItIsOnEvenWithABetterPeakOutOfReach) {
  // A ridge at 500 m sinking 40 m a column (within reach), value 0.6; a
  // peak of 0.9 at 100 m, 400 m away, over the first four columns only: it
  // is gone before the vehicle could get there (4.4 columns at 90 m).
  const ForecastField f = field(6, [](std::size_t k, double z) {
    return std::max(bump(z, 500 + 40.0 * k, 0.6), k <= 3 ? bump(z, 100, 0.9) : 0.0);
  });
  const ForecastDecision d = forecast_depth(f, 500, kOptions);
  ASSERT_EQ(d.choice, ForecastChoice::kRidge);
  ASSERT_EQ(d.path_depth_m.size(), 6u);
  EXPECT_EQ(d.path_depth_m[0], 500);
  // On the ridge at every column's time (the end of one window, the start
  // of the next: between the ridge's depths in the two, give or take the
  // field's 50 m spacing).
  for (std::size_t k = 1; k < 6; ++k) {
    EXPECT_GE(d.path_depth_m[k], 500 + 40.0 * (k - 1) - 25) << k;
    EXPECT_LE(d.path_depth_m[k], 500 + 40.0 * k + 25) << k;
  }
  expect_flyable(d, kOptions);
  EXPECT_DOUBLE_EQ(d.path_time_s[1], 120);
  EXPECT_NEAR(d.depth_after(500, 60), 0.5 * (500 + d.path_depth_m[1]), 1e-9);
  EXPECT_NEAR(d.depth_after(500, 360), d.path_depth_m[3], 1e-9);
  EXPECT_NEAR(d.depth_after(500, 1e6), d.path_depth_m[5], 1e-9);
  // When the 0.9 peak lasts (every column, and so past the horizon) it
  // pays for the 4.4 columns of transit many times over: a ridge that is
  // no longer the best is left for it.
  const ForecastField g = field(11, [](std::size_t k, double z) {
    return std::max(bump(z, 500 + 40.0 * k, 0.6), bump(z, 100, 0.9));
  });
  const ForecastDecision e = forecast_depth(g, 500, kOptions);
  EXPECT_EQ(e.choice, ForecastChoice::kOptimum);
  EXPECT_NEAR(e.target_depth_m, 100, 1e-9);
  EXPECT_LT(e.depth_after(500, 120), 500);  // it leaves now, upward
  // The same ridge alone is followed to the horizon.
  const ForecastField alone = field(11, [](std::size_t k, double z) { return bump(z, 500 + 40.0 * k, 0.6); });
  const ForecastDecision a = forecast_depth(alone, 500, kOptions);
  ASSERT_EQ(a.choice, ForecastChoice::kRidge);
  EXPECT_NEAR(a.path_depth_m[10], 900, 25);
  EXPECT_NEAR(a.depth_after(500, 1200), a.path_depth_m[10], 1e-9);
}

TEST(GramDepthForecast, ARidgeThatEndsWithinTheHorizonIsLeftForTheReachableOptimum) {
  // The same ridge fades out after column 5: not followed.
  const ForecastField f = field(11, [](std::size_t k, double z) {
    return std::max(k <= 5 ? bump(z, 500 + 40.0 * k, 0.6) : 0.0, bump(z, 100, 0.9));
  });
  const ForecastDecision d = forecast_depth(f, 500, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kOptimum);
  EXPECT_NEAR(d.target_depth_m, 100, 1e-9);
  EXPECT_NEAR(d.target_objective, 0.9, 1e-12);
  // 400 m away at 90 m a column: the earliest it can be there is the
  // fifth column (600 s); the plan goes at once, as fast as it may.
  EXPECT_DOUBLE_EQ(d.target_time_s, 600);
  EXPECT_NEAR(d.vertical_rate_mps, 400.0 / 600, 1e-12);
  EXPECT_NEAR(d.depth_after(500, 120), 410, 1e-9);
  expect_flyable(d, kOptions);
}

TEST(GramDepthForecast, AVehicleOffTheRidgeIsNotOnItAndHeadsForIt) {
  // 150 m above the ridge's peak its own objective is far below the peak's.
  const ForecastField f = field(11, [](std::size_t k, double z) { return bump(z, 500 + 40.0 * k, 0.6) + 0.01; });
  const ForecastDecision d = forecast_depth(f, 350, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kOptimum);
  EXPECT_NEAR(d.depth_after(350, 120), 440, 1e-9);  // down at full speed
  EXPECT_NEAR(d.path_depth_m[10], 900, 25);         // then along the ridge
}

TEST(GramDepthForecast, ItTakesALitPathRatherThanCrossAShadowZone) {
  // Lit (0.7) everywhere but a better layer (0.9 at 100 m) and, for the
  // first four columns, a shadow zone from 150 to 400 m (raw objective 0)
  // between the vehicle (450 m) and the layer. Straight up crosses it;
  // waiting below it until it clears, then rising, is lit all the way.
  auto steer = [](std::size_t, double z) { return std::max(bump(z, 100, 0.9), 0.7); };
  auto shadowed = [](std::size_t k, double z) { return k <= 3 && z >= 150 && z <= 400; };
  auto raw = [&](std::size_t k, double z) { return shadowed(k, z) ? 0.0 : steer(k, z); };
  const ForecastDecision d = forecast_depth(field(11, steer, raw), 450, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kOptimum);
  for (std::size_t k = 0; k < d.path_depth_m.size(); ++k) EXPECT_FALSE(shadowed(k, d.path_depth_m[k])) << k;
  EXPECT_NEAR(d.target_depth_m, 100, 1e-9);  // it still gets to the layer
  expect_flyable(d, kOptions);
  // Without the shadow zone it rises at once (in the shadow it stayed below 400 m).
  const ForecastDecision open = forecast_depth(field(11, steer), 450, kOptions);
  EXPECT_LE(open.depth_after(450, 120), 380);  // 360 at full speed; any path there by 480 s ties
  EXPECT_NEAR(open.target_depth_m, 100, 1e-9);
}

TEST(GramDepthForecast, AVehicleStartingInAShadowMayLeaveIt) {
  // Near the surface in a shadow (0 above 200 m), lit below.
  auto steer = [](std::size_t, double z) { return z < 200 ? 0.0 : bump(z, 400, 0.8) + 0.1; };
  const ForecastDecision d = forecast_depth(field(11, steer), 20, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kOptimum);
  EXPECT_NEAR(d.target_depth_m, 400, 10);
  EXPECT_NEAR(d.depth_after(20, 120), 110, 1e-9);
}

TEST(GramDepthForecast, ItFollowsACurvingBandWhereAStraightLineCutsAcrossIt) {
  // A narrow band (30 m) that sinks 80 m a column for five columns and then
  // rises as fast: the best points within the horizon are on it at both
  // ends, and the straight line between them runs through nothing. The
  // plan keeps to the band: at each column's time (the end of one window
  // and the start of the next) between the band's depths in the two.
  auto centre = [](std::size_t k) { return k <= 5 ? 300 + 80.0 * k : 700 - 80.0 * (k - 5.0); };
  const ForecastField f = field(11, [&](std::size_t k, double z) { return bump(z, centre(k), 0.8, 30) + 0.01; });
  const ForecastDecision d = forecast_depth(f, 300, kOptions);
  for (std::size_t k = 1; k < 11; ++k) {
    EXPECT_GE(d.path_depth_m[k], std::min(centre(k - 1), centre(k)) - 25) << k;
    EXPECT_LE(d.path_depth_m[k], std::max(centre(k - 1), centre(k)) + 25) << k;
  }
  expect_flyable(d, kOptions);
}

TEST(GramDepthForecast, ABandOutOfReachWithinTheHorizonStillDrawsItThroughTheTerminalValue) {
  // Nothing within reach of 100 m over 6 columns (450 m); a band at 900 m
  // (800 m away) from the horizon on: with the terminal value the plan
  // starts down now; without it (terminal_s 0) it holds.
  const ForecastField f = field(6, [](std::size_t, double z) { return z >= 850 ? 0.6 : 0.0; });
  const ForecastDecision d = forecast_depth(f, 100, kOptions);
  EXPECT_EQ(d.choice, ForecastChoice::kOptimum);
  EXPECT_NEAR(d.depth_after(100, 120), 190, 1e-9);
  ForecastOptions myopic = kOptions;
  myopic.terminal_s = 0;
  const ForecastDecision m = forecast_depth(f, 100, myopic);
  EXPECT_EQ(m.choice, ForecastChoice::kHold);
  EXPECT_EQ(m.depth_after(100, 120), 100);
}

TEST(GramDepthForecast, AVerySlowVehicleStaysWithinTheWorkBound) {
  // 1 mm/s: a 1000 m field would be 10^6 plan depths at the reach's step
  // and the default terminal 10^6 s; bounded (4000 depths, 480 columns
  // past the horizon), it cannot move on the plan's grid and holds.
  ForecastOptions slow = kOptions;
  slow.vertical_speed_mps = 0.001;
  const ForecastDecision d = forecast_depth(field(11, [](std::size_t, double z) { return bump(z, 900, 0.9) + 0.1; }), 500, slow);
  expect_flyable(d, slow);
  EXPECT_EQ(d.depth_after(500, 120), 500);
}

TEST(GramDepthForecast, OnAFlatFieldItHoldsItsDepth) {
  // Ties go to the smallest move.
  const ForecastDecision d = forecast_depth(field(11, [](std::size_t, double) { return 0.5; }), 330, kOptions);
  for (double z : d.path_depth_m) EXPECT_EQ(z, 330);
  EXPECT_NEAR(d.expected_score, 0.5, 1e-12);
}

TEST(GramDepthForecast, TheScoreNotTheSteeringObjectiveIsWhatThePlanGathers) {
  // The steering objective prefers 200 m, the score (a reception
  // probability) 700 m: the plan follows the score.
  ForecastField f = field(11, [](std::size_t, double z) { return std::max(bump(z, 200, 0.9), bump(z, 700, 0.5)); });
  f.score = f.steer;
  for (auto& column : f.score)
    for (std::size_t j = 0; j < column.size(); ++j) column[j] = bump(f.depth_m[j], 700, 0.95) + 0.01;
  const ForecastDecision d = forecast_depth(f, 450, kOptions);
  EXPECT_GT(d.depth_after(450, 120), 450);
  EXPECT_NEAR(d.target_depth_m, 700, 1e-9);
}

TEST(GramDepthForecast, ForbiddenDepthsAreNeitherTargetsNorPassages) {
  // The best is below the allowed depths (max 600 m): it takes the best allowed.
  ForecastField f = field(11, [](std::size_t, double z) { return std::max(bump(z, 900, 1.0), bump(z, 400, 0.5)); });
  for (auto& column : f.allowed)
    for (std::size_t j = 0; j < column.size(); ++j) column[j] = f.depth_m[j] <= 600;
  const ForecastDecision d = forecast_depth(f, 350, kOptions);
  for (double z : d.path_depth_m) EXPECT_LE(z, 600);
  EXPECT_NEAR(d.target_depth_m, 400, 1e-9);
  // Nor passages: a forbidden band (600-700 m) between the vehicle and a
  // better layer below it keeps the plan above it.
  ForecastField g = field(11, [](std::size_t, double z) { return std::max(bump(z, 900, 1.0), 0.2); });
  for (auto& column : g.allowed)
    for (std::size_t j = 0; j < column.size(); ++j) column[j] = g.depth_m[j] < 600 || g.depth_m[j] > 700;
  const ForecastDecision e = forecast_depth(g, 500, kOptions);
  for (double z : e.path_depth_m) EXPECT_LT(z, 600);
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
  o = kOptions;
  o.terminal_s = -1;
  EXPECT_EQ(*validate_forecast_options(o), "terminal_s must be in [0, 86400] s");
  ForecastField scored = f;
  scored.score = scored.steer;
  scored.score[1].pop_back();
  EXPECT_EQ(*validate_forecast_field(scored), "forecast column 1 does not have one value per depth");
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
  // Without the bias (no low-pass at all) the plan's best point is higher.
  DepthObjectiveRequest unbiased = q;
  unbiased.forecast->caustic_uncertainty_m = 0;
  const DepthObjectiveResult u = compute_depth_objective(tl, env, unbiased);
  EXPECT_LT(u.forecast->decision.target_depth_m, f.decision.target_depth_m);
  EXPECT_LE(u.forecast->decision.target_depth_m, 325);

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

TEST(GramDepthForecastField, WithTheModemsCurveTheScoreIsTheChanceOfDecodingInEachWindow) {
  // The layer's loss grows 1 dB per 200 m of range, so each window has its
  // own best signal excess; the score must be the reception probability of
  // each window's own signal excess (no low-pass), whatever the rescaling
  // of the steering objective across the columns.
  Environment env;
  for (auto [z, c] : {std::pair{0.0, 1500.0}, {500.0, 1500.0}}) {
    auto* p = env.add_sound_speed();
    p->set_depth_m(z);
    p->set_speed_mps(c);
  }
  TransmissionLoss grid = layered_from_2km();
  for (std::size_t j = 0; j < grid.depth_m.size(); ++j)
    for (std::size_t i = 0; i < grid.range_m.size(); ++i) {
      double& v = grid.tl_db[j * grid.range_m.size() + i];
      if (std::isfinite(v)) v += (grid.range_m[i] - 2000) / 200 + std::abs(grid.depth_m[j] - 300) / 10;
    }
  const std::vector<TransmissionLoss> tl{grid};
  DepthObjectiveRequest q;
  q.range_m = 2000;
  q.speed_mps = 1.5;
  q.horizon_s = 120;
  q.limits = {5, 480, 10};
  SonarOptions sonar;
  sonar.source_level_db = 190;
  sonar.noise_level_db = 105;
  q.sonar = sonar;
  q.forecast = DepthForecastRequest{};
  q.forecast->forecast_horizon_s = 1200;
  q.forecast->current_depth_m = 300;
  q.forecast->caustic_uncertainty_m = 0;
  q.forecast->reception = ReceptionCurve{10, 0.5};
  const DepthObjectiveResult r = compute_depth_objective(tl, env, q);
  const ForecastField& f = r.forecast->field;
  ASSERT_EQ(f.score.size(), f.time_s.size());
  std::size_t lit = 0;
  for (std::size_t k = 0; k < f.time_s.size(); ++k) {
    DepthObjectiveRequest column = q;
    column.forecast.reset();
    column.range_m = 2000 + 1.5 * f.time_s[k];
    const DepthObjectiveResult one = compute_depth_objective(tl, env, column);
    for (std::size_t j = 0; j < f.depth_m.size(); ++j) {
      if (!(f.raw[k][j] > 0)) continue;  // shadow: the planner scores it 0
      ++lit;
      EXPECT_NEAR(f.score[k][j], reception_probability(*q.forecast->reception, one.signal_excess_db[j]), 1e-9)
          << k << " " << j;
    }
  }
  EXPECT_GT(lit, 20u);
  // Without the curve there is no score: the plan gathers the objective.
  q.forecast->reception.reset();
  EXPECT_TRUE(compute_depth_objective(tl, env, q).forecast->field.score.empty());
}

}  // namespace
}  // namespace acomms::gram
