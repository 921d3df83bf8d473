// The depth-adaptation evaluation as a library, on small environments built
// here (fast): the adaptive vehicle's motion limits, determinism, common
// random numbers, the expectation the draws converge to, the honest verdict
// when adapting cannot help, and errors that name the field.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/depth_adaptation.h"
#include "eval/depth_adaptation_sweep.h"

namespace acomms::eval {
namespace {

// 100 m of water at 2 kHz, a thermocline between 10 and 30 m, a sand bottom.
gram::Environment small_thermocline() {
  gram::Environment env;
  env.set_frequency_hz(2000);
  for (auto [z, c] : {std::pair{0.0, 1536.0}, {10.0, 1535.6}, {30.0, 1511.8}, {100.0, 1511.0}}) {
    auto* p = env.add_sound_speed();
    p->set_depth_m(z);
    p->set_speed_mps(c);
  }
  env.mutable_bottom()->set_kind(gram::Boundary::HALF_SPACE);
  env.mutable_bottom()->mutable_half_space()->set_speed_mps(1650);
  env.mutable_bottom()->mutable_half_space()->set_density_ratio(1.9);
  env.mutable_bottom()->mutable_half_space()->set_attenuation_np_per_m(0.8 * 2000 / (8.6859 * 1650));
  env.set_field_mode(gram::INCOHERENT);
  env.set_launch_angle_min_deg(-80);
  env.set_launch_angle_max_deg(80);
  return env;
}

DepthAdaptationConfig small_config() {
  DepthAdaptationConfig c;
  c.max_range_m = 1200;
  c.fixed_depths_m = {10, 50, 80};
  c.bin_m = 400;
  c.range_step_m = 20;
  c.depth_step_m = 5;
  c.laps = 10;
  c.physics.noise_level_db = 128;  // puts the edge of reception inside 1.2 km (p 0.7-0.9 overall)
  return c;
}

TEST(DepthAdaptation, AdaptiveVehicleMovesNoFasterThanAllowedAndStaysWithinItsLimits) {
  const DepthAdaptationConfig c = small_config();
  const DepthAdaptationResult r = run_depth_adaptation(small_thermocline(), c);
  ASSERT_GT(r.adaptive_path.size(), 10u);
  bool moved = false;
  for (std::size_t i = 1; i < r.adaptive_path.size(); ++i) {
    const AdaptiveSample& a = r.adaptive_path[i - 1];
    const AdaptiveSample& b = r.adaptive_path[i];
    EXPECT_LE(std::abs(b.depth_m - a.depth_m), c.vertical_speed_mps * (b.time_s - a.time_s) + 1e-9) << "packet " << i;
    EXPECT_GE(b.target_m, c.limits.min_depth_m);
    EXPECT_LE(b.target_m, 100 - c.limits.min_altitude_m);
    moved = moved || b.depth_m != c.start_depth_m;
  }
  EXPECT_TRUE(moved) << "the adaptive vehicle never left its start depth";
  EXPECT_EQ(r.strategies.size(), c.fixed_depths_m.size() + 1);
  EXPECT_EQ(r.strategies.back().name, "adaptive");
  EXPECT_EQ(r.bin_edges_m, (std::vector<double>{0, 400, 800, 1200}));
}

TEST(DepthAdaptation, SameSeedSameNumbersAndStrategiesShareTheirDraws) {
  DepthAdaptationConfig c = small_config();
  const DepthAdaptationResult a = run_depth_adaptation(small_thermocline(), c);
  const DepthAdaptationResult b = run_depth_adaptation(small_thermocline(), c);
  EXPECT_EQ(format_depth_adaptation_json(c, a), format_depth_adaptation_json(c, b));
  // Two strategies at the same fixed depth see the same physics and the
  // same draws: identical counts, bin by bin.
  c.fixed_depths_m = {50, 50};
  const DepthAdaptationResult twins = run_depth_adaptation(small_thermocline(), c);
  EXPECT_EQ(twins.strategies[0].received, twins.strategies[1].received);
  c.seed = 2;
  const DepthAdaptationResult other = run_depth_adaptation(small_thermocline(), c);
  EXPECT_EQ(other.strategies[0].expected, twins.strategies[0].expected);  // same physics
}

TEST(DepthAdaptation, DrawsConvergeToTheModelledExpectation) {
  DepthAdaptationConfig c = small_config();
  c.laps = 2000;
  const DepthAdaptationResult r = run_depth_adaptation(small_thermocline(), c);
  std::size_t uncertain = 0;  // strategies whose packets are neither sure nor hopeless
  for (const StrategyResult& s : r.strategies) {
    const double p = s.expected_overall, n = s.total_sent;
    uncertain += p > 0.05 && p < 0.95;
    // Within 5 standard errors of a binomial proportion.
    EXPECT_NEAR(s.receipt_overall(), p, 5 * std::sqrt(p * (1 - p) / n) + 1e-12) << s.name;
  }
  EXPECT_GE(uncertain, 2u) << "the noise level leaves nothing to draw: the test checks nothing";
}

TEST(DepthAdaptation, SaysSoWhenAdaptingCannotHelp) {
  // So little noise that every packet decodes at every depth: no strategy
  // can do better than another.
  DepthAdaptationConfig c = small_config();
  c.physics.noise_level_db = -100;
  const DepthAdaptationResult r = run_depth_adaptation(small_thermocline(), c);
  for (const StrategyResult& s : r.strategies) EXPECT_EQ(s.total_received, s.total_sent) << s.name;
  EXPECT_FALSE(r.adaptive_beats_every_fixed);
  EXPECT_FALSE(r.adaptive_expected_beats_every_fixed);
  const std::string table = format_depth_adaptation_table(c, r);
  EXPECT_NE(table.find("adaptation does NOT help here"), std::string::npos) << table;
}

TEST(DepthAdaptation, AVehicleModelEqualToTheWaterDecidesAsTheWaterAndAWrongOneDecidesOtherwise) {
  const DepthAdaptationConfig c = small_config();
  const gram::Environment water = small_thermocline();
  const DepthAdaptationResult perfect = run_depth_adaptation(water, c);
  const DepthAdaptationResult same = run_depth_adaptation(water, c, &water);
  EXPECT_TRUE(same.separate_model);
  EXPECT_FALSE(perfect.separate_model);
  EXPECT_EQ(same.strategies.back().received, perfect.strategies.back().received);
  // A vehicle that believes the water is isovelocity (no thermocline).
  gram::Environment believed = water;
  for (auto& p : *believed.mutable_sound_speed()) p.set_speed_mps(1511.0);
  const DepthAdaptationResult wrong = run_depth_adaptation(water, c, &believed);
  bool differs = false;
  for (std::size_t i = 0; i < wrong.adaptive_path.size(); ++i)
    differs = differs || wrong.adaptive_path[i].target_m != perfect.adaptive_path[i].target_m;
  EXPECT_TRUE(differs) << "the believed profile changed no decision";
  // Fixed depths do not depend on what the vehicle believes.
  EXPECT_EQ(wrong.strategies[0].received, perfect.strategies[0].received);
}

TEST(DepthAdaptation, ErrorsNameTheFieldAndTheBound) {
  DepthAdaptationConfig c = small_config();
  c.fixed_depths_m = {10, 150};
  try {
    run_depth_adaptation(small_thermocline(), c);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("fixed_depths_m = 150 must lie in the water column (0, 100) m"),
              std::string::npos)
        << e.what();
  }
  c = small_config();
  c.horizon_s = 0;
  EXPECT_THROW(run_depth_adaptation(small_thermocline(), c), std::invalid_argument);
  c = small_config();
  c.max_range_m = 10;  // not beyond the start range
  try {
    run_depth_adaptation(small_thermocline(), c);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_range_m"), std::string::npos) << e.what();
  }
}

// The sweep (depth_adaptation_sweep.h): each point is the replay at that
// value; receipt falls as the noise rises; an excess loss of e dB over an
// ambient NL is the same link as NL + e with none (SNR = SL − TL − e − NL).
TEST(DepthAdaptationSweep, EachPointIsTheReplayAtThatValueAndReceiptFallsWithTheNoise) {
  DepthAdaptationConfig c = small_config();
  c.laps = 4;
  const gram::Environment env = small_thermocline();
  const std::vector<SweepPoint> points = run_depth_adaptation_sweep(env, c, nullptr, SweepQuantity::kNoise, {120, 136, 8});
  ASSERT_EQ(points.size(), 3u);
  for (std::size_t i = 0; i < points.size(); ++i) {
    DepthAdaptationConfig one = c;
    one.physics.noise_level_db = 120 + 8.0 * i;
    const DepthAdaptationResult r = run_depth_adaptation(env, one);
    const StrategyResult& a = r.strategies.back();
    EXPECT_EQ(points[i].value, 120 + 8.0 * i);
    EXPECT_EQ(points[i].adaptive, a.receipt_overall()) << i;
    EXPECT_EQ(points[i].best_fixed, r.strategies[r.best_fixed].name) << i;
    EXPECT_EQ(points[i].fixed, r.strategies[r.best_fixed].receipt_overall()) << i;
    EXPECT_NEAR(points[i].adaptive_se, std::sqrt(a.receipt_overall() * (1 - a.receipt_overall()) / a.total_sent), 1e-15);
    if (i > 0) {
      EXPECT_LE(points[i].adaptive, points[i - 1].adaptive) << i;
      EXPECT_LE(points[i].fixed, points[i - 1].fixed) << i;
    }
  }
  EXPECT_LT(points.back().adaptive, points.front().adaptive) << "the range must cross the edge of reception";
  const double se = std::hypot(points[1].adaptive_se, points[1].fixed_se);
  if (se > 0) EXPECT_NEAR(points[1].margin_se, (points[1].adaptive - points[1].fixed) / se, 1e-12);
}

TEST(DepthAdaptationSweep, AnExcessLossIsTheSameLinkAsThatMuchMoreNoise) {
  DepthAdaptationConfig c = small_config();
  c.laps = 4;
  c.physics.noise_level_db = 120;
  const gram::Environment env = small_thermocline();
  const auto by_excess = run_depth_adaptation_sweep(env, c, nullptr, SweepQuantity::kExcessLoss, {0, 16, 8});
  const auto by_noise = run_depth_adaptation_sweep(env, c, nullptr, SweepQuantity::kNoise, {120, 136, 8});
  ASSERT_EQ(by_excess.size(), by_noise.size());
  for (std::size_t i = 0; i < by_excess.size(); ++i) {
    // The same draws against SNRs equal up to rounding: at most a packet apart.
    EXPECT_NEAR(by_excess[i].adaptive, by_noise[i].adaptive, 0.02) << i;
    EXPECT_NEAR(by_excess[i].fixed, by_noise[i].fixed, 0.02) << i;
  }
  EXPECT_LT(by_excess.back().adaptive, by_excess.front().adaptive);
}

TEST(DepthAdaptationSweep, RangesAndQuantitiesAreCheckedWithMessagesThatSayWhy) {
  EXPECT_EQ(sweep_values(parse_sweep_range("100:112:2")), (std::vector<double>{100, 102, 104, 106, 108, 110, 112}));
  EXPECT_EQ(sweep_values(parse_sweep_range("-3:3:2.5")), (std::vector<double>{-3, -0.5, 2}));
  EXPECT_EQ(sweep_values(parse_sweep_range("0:0.3:0.1")).size(), 4u) << "TO on the grid, up to rounding";
  auto error = [](const std::string& text) {
    try {
      parse_sweep_range(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("100:112"), "sweep range \"100:112\" is not FROM:TO:STEP (in dB, e.g. 100:112:2)");
  EXPECT_EQ(error("100:x:2"), "sweep range \"100:x:2\": TO \"x\" is not a number (FROM:TO:STEP in dB, e.g. 100:112:2)");
  EXPECT_EQ(error("100:112:0"), "sweep range \"100:112:0\": STEP must be > 0");
  EXPECT_EQ(error("112:100:2"), "sweep range \"112:100:2\": TO must be at least FROM");
  EXPECT_EQ(error("0:1000:1"), "sweep range \"0:1000:1\" has more than 200 values: raise STEP");
  EXPECT_EQ(sweep_quantity_from_string("excess-loss"), SweepQuantity::kExcessLoss);
  EXPECT_THROW(sweep_quantity_from_string("depth"), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::eval
