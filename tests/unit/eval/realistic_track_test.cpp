// The realistic track generator (daemon/eval/realistic_track.h): the same
// seed gives the same fixes, the effects it documents are in the tracks at
// the documented magnitudes, and its arithmetic agrees with libm.

#include "eval/realistic_track.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "eval/depth_controller.h"
#include "eval/track_math.h"

namespace acomms::eval {
namespace {

using telemetry::Fix;

TEST(TrackMath, AgreesWithTheLibraryToRoundingError) {
  for (double x = -20; x < 20; x += 0.0137) {
    // (the reduction by 2 pi costs a few ulps of x)
    ASSERT_NEAR(track_sin(x), std::sin(x), 1e-14) << x;
    ASSERT_NEAR(track_cos(x), std::cos(x), 1e-14) << x;
  }
  for (double a = -3.14; a < 3.14; a += 0.0131) {
    for (double r : {1e-3, 1.0, 250.0}) {
      ASSERT_NEAR(track_atan2(r * std::sin(a), r * std::cos(a)), std::atan2(r * std::sin(a), r * std::cos(a)), 2e-15)
          << a;
    }
  }
  EXPECT_EQ(track_atan2(0, -1), std::atan2(0.0, -1.0));
  EXPECT_EQ(track_atan2(0, 0), 0.0);
  for (double x = 0; x > -50; x -= 0.0173) ASSERT_NEAR(track_exp_neg(x), std::exp(x), 1e-14 * std::exp(x)) << x;
}

TEST(TrackMath, NormalDeviatesHaveUnitVariance) {
  TrackNoise noise(9);
  double sum = 0, sum_sq = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double v = noise.normal();
    sum += v;
    sum_sq += v * v;
  }
  EXPECT_NEAR(sum / n, 0, 0.01);
  EXPECT_NEAR(sum_sq / n, 1, 0.01);
}

TEST(DepthController, OvershootsANewDepthByAboutAMetreAtTheRateLimit) {
  DepthController depth(60, 0.5, 0.5);
  double deepest = 0, fastest = 0;
  for (int t = 0; t < 600; ++t) {
    depth.step(40, 1);
    deepest = std::max(deepest, depth.depth());
    fastest = std::max(fastest, depth.rate());
  }
  EXPECT_DOUBLE_EQ(fastest, 0.5);
  EXPECT_GT(deepest, 40.5);
  EXPECT_LT(deepest, 43);
  EXPECT_NEAR(depth.depth(), 40, 0.05);  // settled
}

TEST(RealisticTrack, TheSameSeedGivesTheSameFixesAndAnotherSeedOthers) {
  for (TrackKind kind : {TrackKind::kAuv, TrackKind::kGlider}) {
    const std::vector<Fix> a = generate_realistic_track(kind, 4, 3600);
    const std::vector<Fix> b = generate_realistic_track(kind, 4, 3600);
    const std::vector<Fix> c = generate_realistic_track(kind, 5, 3600);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a[i].time_s, b[i].time_s);
      ASSERT_EQ(a[i].position_m, b[i].position_m) << i;  // bit for bit
    }
    EXPECT_NE(a.back().position_m, c.back().position_m);
  }
}

struct Steps {
  std::vector<double> jumps;  // horizontal steps between fixes above 5 m
  double median_speed = 0;    // over ground, m/s
  double deepest = 0;
  int surfacings = 0;  // arrivals at z = 0 from below 3 m
};

Steps steps_of(const std::vector<Fix>& fixes) {
  Steps s;
  std::vector<double> speeds;
  bool below = false;
  for (size_t i = 1; i < fixes.size(); ++i) {
    const double dt = fixes[i].time_s - fixes[i - 1].time_s;
    const double d = std::hypot(fixes[i].position_m[0] - fixes[i - 1].position_m[0],
                                fixes[i].position_m[1] - fixes[i - 1].position_m[1]);
    if (d > 5) s.jumps.push_back(d);
    speeds.push_back(d / dt);
    s.deepest = std::max(s.deepest, -fixes[i].position_m[2]);
    if (-fixes[i].position_m[2] > 3) below = true;
    if (below && fixes[i].position_m[2] == 0) {
      ++s.surfacings;
      below = false;
    }
  }
  std::nth_element(speeds.begin(), speeds.begin() + speeds.size() / 2, speeds.end());
  s.median_speed = speeds[speeds.size() / 2];
  return s;
}

TEST(RealisticTrack, TorpedoAuvSurfacesAndItsGpsFixesJumpTheNavigationByTensOfMetres) {
  const std::vector<Fix> fixes = generate_realistic_track(TrackKind::kAuv, 1, 4 * 3600);
  ASSERT_EQ(fixes.size(), 4u * 3600 + 1);  // 1 Hz, no gaps
  const Steps s = steps_of(fixes);
  EXPECT_GE(s.surfacings, 3);  // every 30-75 min
  EXPECT_GE(s.jumps.size(), 2u);
  EXPECT_GE(*std::max_element(s.jumps.begin(), s.jumps.end()), 10.0);
  EXPECT_LE(*std::max_element(s.jumps.begin(), s.jumps.end()), 150.0);
  // 1.5 m/s through the water, plus or minus a current of a few tenths
  EXPECT_GT(s.median_speed, 1.0);
  EXPECT_LT(s.median_speed, 2.0);
  EXPECT_NE(s.median_speed, 1.5);
  EXPECT_GT(s.deepest, 20);
  EXPECT_LT(s.deepest, 80);
}

TEST(RealisticTrack, GliderSawtoothsToAFewHundredMetresAtAFewTenthsOfAMetrePerSecond) {
  const std::vector<Fix> fixes = generate_realistic_track(TrackKind::kGlider, 1, 9 * 3600);
  const Steps s = steps_of(fixes);
  EXPECT_GE(s.surfacings, 2);
  EXPECT_GE(s.jumps.size(), 1u);  // a dead-reckoning correction at a fix
  EXPECT_GT(s.median_speed, 0.1);
  EXPECT_LT(s.median_speed, 0.6);
  EXPECT_GT(s.deepest, 80);
  EXPECT_LT(s.deepest, 215);
  // the sawtooth: a dive through 50 m every half hour or so (80-200 m at
  // 0.15 m/s), not once and not on noise (0.1 m) or waves
  int dives = 0;
  for (size_t i = 1; i < fixes.size(); ++i) dives += fixes[i - 1].position_m[2] > -50 && fixes[i].position_m[2] <= -50;
  EXPECT_GE(dives, 10);
  EXPECT_LE(dives, 20);
}

TEST(RealisticTrack, StaysInsideTheTelemetryRegionForDays) {
  for (TrackKind kind : {TrackKind::kAuv, TrackKind::kGlider}) {
    double farthest = 0;
    for (const Fix& fix : generate_realistic_track(kind, 2, 3 * 86400))
      farthest = std::max({farthest, std::fabs(fix.position_m[0]), std::fabs(fix.position_m[1])});
    EXPECT_LT(farthest, 12000);
  }
}

}  // namespace
}  // namespace acomms::eval
