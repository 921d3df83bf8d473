// Issue 32, the deep ocean (Schneider 2013 §4.4): on a deep Munk channel
// (examples/deep_munk.env: 5000 m, 2 kHz, incoherent, the buoy's modem at
// 200 m), a vehicle running 20 -> 60 km and back from 20 m, deciding every
// 120 s, the forecast looking an hour ahead (cut at the turn).
// Vertical speed 0.51 m/s: 20 deg of pitch at 1.5 m/s is 1.5 sin 20 deg =
// 0.51 m/s (the issue says 0.75, which is 30 deg).
// The noise, by a rule fixed before comparing strategies: "the link
// marginal" is where the best fixed depth receives about 0.4 (the middle
// of 0.3-0.5): NL 93 dB (4000 m receives 0.398; 90 dB gives 0.535, 95 dB
// 0.289), falling 3 dB/km below the critical depth (4800 m in this profile:
// at the vehicle's deepest allowed depth, so the noise profile barely acts).
// Standard errors: SE = sqrt(p(1-p)/n) per strategy over its n packets, the
// difference's SE their root sum of squares (conservative, since the
// strategies share their draws). Cost: one model run (1500 beams, 101
// depths x 656 ranges) and the replay: about 2.5 s at 2 threads.
//
// The criterion: the forecast beats the next-window strategy AND
// every fixed depth by two SEs. Measured (forecast / next window / best
// fixed depth (4000 m) / perfect foresight, the last a dynamic programme
// over every packet's true probability on a 10.2 m grid within 0.51 m/s,
// computed by hand, not in this file):
//   NL 90: 0.867 / 0.829 / 0.535 / 0.869, forecast - next window 9.9 SEs
//   NL 93: 0.796 / 0.752 / 0.398 / 0.815, 9.8 SEs (over 4000 m: 84 SEs)
//   NL 95: 0.666 / 0.632 / 0.289 / 0.692, 6.7 SEs
// (SEs 0.0025-0.0037 per strategy; the README has the table.)
// History, and why: the thesis's rule read literally (stay on a ridge, else
// head for the earliest near-best reachable point without crossing a
// shadow) received 0.478 at NL 93: a target is one point, the packets are
// the path, and the straight line to the point cut across the curving band
// the next window follows. A first dynamic programme over the same field
// received 0.55-0.60, and the reason, measured per decision, was its
// horizon's end: from 20 m an hour at 0.51 m/s reaches 1.8 km, the
// refracted band at 3.2-3.7 km is out of reach within it, so every path
// scored 0 and the plan held at 20 m while the next window dived. With a
// terminal value (the last column's field held as long as crossing the
// depths takes) the same planner dives at once and receives 0.796; scoring
// windows by the reception probability rather than the (linear) objective
// adds little at NL 93 (0.793 with the objective) and more where the link
// is weaker (NL 95: 0.666 against 0.651), removing the caustic bias
// (no low-pass) changes 0.796 to 0.798, and horizons of 1800, 3600 and
// 7200 s receive the same 0.796. Compared packet by packet with the
// perfect-foresight path: all three (forecast, next window, bound) dive at
// full speed from 20 m to the band at 3.7 km (32 km), and then keep within
// tens of metres of one another; the next window loses where its depth
// falls into a narrow shadow (p = 0 at 450 m near 55 km, 750 m near 53 km,
// 3000 m near 40.6 km on the way back), which the forecast's plan, close
// to the bound's path there, avoids. The planner is gram/depth_forecast.h.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "eval/depth_adaptation.h"
#include "gram/bellhop_import.h"

namespace acomms::eval {
namespace {

DepthAdaptationConfig deep_config() {
  DepthAdaptationConfig c;
  c.buoy_depth_m = 200;
  c.start_range_m = 20000;
  c.max_range_m = 60000;
  c.speed_mps = 1.5;
  c.send_interval_s = 60;
  c.start_depth_m = 20;
  c.vertical_speed_mps = 0.51;  // 1.5 m/s x sin 20 deg
  c.horizon_s = 120;
  c.fixed_depths_m = {100, 300, 500, 1000, 1500, 2000, 2500, 3000, 3500, 4000, 4500};
  c.limits = {10, 4800, 100};
  c.bin_m = 5000;
  c.range_step_m = 100;
  c.depth_step_m = 50;
  c.laps = 20;
  c.threads = 2;
  c.physics.noise_level_db = 93;  // the best fixed depth receives ~0.4 (see above)
  c.noise_decrease_db_per_km = 3;
  c.forecast = true;
  c.forecast_horizon_s = 3600;
  return c;
}

const StrategyResult& named(const DepthAdaptationResult& r, const std::string& name) {
  for (const StrategyResult& s : r.strategies)
    if (s.name == name) return s;
  throw std::runtime_error("no strategy " + name);
}

double margin_se(const StrategyResult& a, const StrategyResult& b) {
  return (a.receipt_overall() - b.receipt_overall()) / std::hypot(receipt_se(a), receipt_se(b));
}

DepthAdaptationResult deep_replay(const DepthAdaptationConfig& c) {
  const gram::Environment env =
      gram::import_bellhop_env_file(std::string(ACOMMS_EXAMPLES_DIR) + "/deep_munk.env").environment;
  const DepthAdaptationResult r = run_depth_adaptation(env, c);
  std::printf("%s", format_depth_adaptation_table(c, r).c_str());
  return r;
}

TEST(DeepForecast, OnADeepMunkChannelTheForecastBeatsEveryFixedDepthWithinItsLimits) {
  const DepthAdaptationConfig c = deep_config();
  const DepthAdaptationResult r = deep_replay(c);
  ASSERT_TRUE(r.critical_depth_m);  // the noise falls below it (about 4800 m in this profile)
  const StrategyResult& forecast = named(r, "forecast");
  for (const StrategyResult& s : r.strategies) {
    if (!s.fixed_depth_m) continue;
    EXPECT_GT(margin_se(forecast, s), 2.0) << "forecast " << forecast.receipt_overall() << " against " << s.name << "'s "
                                           << s.receipt_overall();
  }
  // It moves: from 20 m down into the refracted band and up to the zone.
  ASSERT_EQ(r.forecast_path.size(), r.adaptive_path.size());
  double deepest = 0;
  for (std::size_t i = 1; i < r.forecast_path.size(); ++i) {
    const AdaptiveSample& a = r.forecast_path[i - 1];
    const AdaptiveSample& b = r.forecast_path[i];
    EXPECT_LE(std::abs(b.depth_m - a.depth_m), c.vertical_speed_mps * (b.time_s - a.time_s) + 1e-6) << i;
    EXPECT_GE(b.depth_m, c.limits.min_depth_m - 1e-9);
    EXPECT_LE(b.depth_m, c.limits.max_depth_m + 1e-9);
    deepest = std::max(deepest, b.depth_m);
  }
  EXPECT_GT(deepest, 3000);
}

// The criterion in full.
TEST(DeepForecast, OnADeepMunkChannelTheForecastBeatsTheNextWindowAndEveryFixedDepth) {
  const DepthAdaptationResult r = deep_replay(deep_config());
  const StrategyResult& forecast = named(r, "forecast");
  const StrategyResult& next = named(r, "adaptive");
  EXPECT_GT(margin_se(forecast, next), 2.0) << "forecast " << forecast.receipt_overall() << " against the next window's "
                                            << next.receipt_overall();
  for (const StrategyResult& s : r.strategies) {
    if (!s.fixed_depth_m) continue;
    EXPECT_GT(margin_se(forecast, s), 2.0) << s.name;
  }
}

}  // namespace
}  // namespace acomms::eval
