// The depth-adaptation evaluation as a library, on small environments built
// here (fast): the adaptive vehicle's motion limits, determinism, common
// random numbers, the expectation the draws converge to, the honest verdict
// when adapting cannot help, and errors that name the field.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/depth_adaptation.h"

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

}  // namespace
}  // namespace acomms::eval
