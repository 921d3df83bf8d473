// The depth objective (spec §6): window conventions, validation messages,
// best-depth selection under the vehicle's limits, and an end-to-end run of
// the built-in model.
#include "gram/depth_objective.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gram/bellhop_import.h"
#include "gram/best_depth.h"
#include "gram/depth_lowpass.h"
#include "gram/loss_objective.h"
#include "gram/noise_depth_profile.h"
#include "gram/range_averaged_tl.h"
#include "gram/range_window.h"
#include "gram/sonar_equation.h"
#include "gram/transmission_loss.h"
#include "pekeris_depth_case.h"

namespace acomms::gram {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The message of the std::invalid_argument `f` throws ("" if none).
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

RangeWindowInput window_input(double r0, double speed, double heading, double step = 25) {
  return {r0, speed, heading, 120.0, step};
}

TEST(GramRangeWindow, OpeningLooksAheadFromTheCurrentRange) {
  const RangeWindow w = range_window(window_input(2000, 1.5, 0));
  EXPECT_DOUBLE_EQ(w.begin_m, 2000);
  EXPECT_DOUBLE_EQ(w.end_m, 2180);
  EXPECT_FALSE(w.closing);
  EXPECT_FALSE(w.widened);
}

TEST(GramRangeWindow, PortAndStarboardHeadingsGiveTheSameWindow) {
  const RangeWindow a = range_window(window_input(2000, 1.5, 60));
  const RangeWindow b = range_window(window_input(2000, 1.5, -60));
  EXPECT_DOUBLE_EQ(a.end_m, b.end_m);
  EXPECT_NEAR(a.end_m, 2090, 1e-9);
}

TEST(GramRangeWindow, ClosingLooksBackTowardTheOtherNodeAndStopsAtRangeZero) {
  const RangeWindow w = range_window(window_input(2000, 1.5, 180));
  EXPECT_TRUE(w.closing);
  EXPECT_NEAR(w.delta_r_m, -180, 1e-9);
  EXPECT_NEAR(w.begin_m, 1820, 1e-9);
  EXPECT_DOUBLE_EQ(w.end_m, 2000);
  const RangeWindow near = range_window(window_input(100, 1.5, 180));
  EXPECT_DOUBLE_EQ(near.begin_m, 0);
  EXPECT_DOUBLE_EQ(near.end_m, 100);
}

TEST(GramRangeWindow, AWindowShorterThanTheRangeStepIsWidenedToOneStep) {
  for (double heading : {90.0, 0.0}) {
    const double speed = heading == 0 ? 0.0 : 1.5;  // abeam, or at rest
    const RangeWindow w = range_window(window_input(2000, speed, heading));
    EXPECT_TRUE(w.widened) << heading;
    EXPECT_DOUBLE_EQ(w.begin_m, 2000);
    EXPECT_DOUBLE_EQ(w.end_m, 2025);
  }
}

TEST(GramRangeWindow, BadInputsNameTheFieldAndTheBound) {
  EXPECT_EQ(error_of([] { range_window(window_input(2000, -1, 0)); }),
            "speed_mps = -1 must be a finite number of at least 0");
  EXPECT_EQ(error_of([] { range_window(window_input(2000, NAN, 0)); }),
            "speed_mps = nan must be a finite number of at least 0");
  EXPECT_EQ(error_of([] {
              range_window({2000, 1, 0, 0, 25});
            }),
            "horizon_s = 0 must be a finite number greater than 0");
  EXPECT_EQ(error_of([] { range_window(window_input(2000, 1, kInf)); }),
            "heading_deg = inf must be a finite number of degrees");
  EXPECT_EQ(error_of([] { range_window(window_input(-5, 1, 0)); }),
            "range_m = -5 must be a finite number of at least 0");
  EXPECT_EQ(error_of([] { range_window(window_input(5, 1, 0, 0)); }),
            "range_step_m = 0 must be a finite number greater than 0");
}

// A 3-depth × 4-range grid with chosen TL values.
TransmissionLoss small_grid() {
  TransmissionLoss tl;
  tl.range_m = {0, 100, 200, 300};
  tl.depth_m = {10, 20, 30};
  tl.tl_db = {NAN, 60,   60,   90,  //
              NAN, 60,   70,   90,  //
              NAN, kInf, kInf, 90};
  return tl;
}

TEST(GramRangeAveragedTl, AveragesIntensityNotDecibelsOverTheHalfOpenWindow) {
  const RangeAveragedTl a = range_averaged_tl(small_grid(), {0, 100, 300});
  EXPECT_EQ(a.ranges_in_window, 2u);  // 100 and 200; 300 is the open end
  EXPECT_NEAR(a.h_bar_db[0], 60, 1e-12);
  EXPECT_NEAR(a.h_bar_db[1], -10 * std::log10((1e-6 + 1e-7) / 2), 1e-12);
  EXPECT_EQ(a.h_bar_db[2], kInf);  // shadow everywhere in the window
}

TEST(GramRangeAveragedTl, TheRangeZeroColumnIsLeftOutOfTheMean) {
  const RangeAveragedTl a = range_averaged_tl(small_grid(), {0, 0, 150});
  EXPECT_NEAR(a.h_bar_db[0], 60, 1e-12);
}

TEST(GramRangeAveragedTl, AWindowBeyondTheGridIsAnErrorNamingBoth) {
  EXPECT_EQ(error_of([] {
              range_averaged_tl(small_grid(), {0, 400, 500});
            }),
            "the range window [400, 500) m holds no receiver range (grid ranges: 0 to 300 m)");
  TransmissionLoss irregular = small_grid();
  irregular.irregular = true;
  EXPECT_NE(error_of([&] {
              range_averaged_tl(irregular, {0, 0, 500});
            }).find("irregular"),
            std::string::npos);
}

TEST(GramInstanceAverage, TheBandBracketsTheMeanAndSpreadsWithTheInstances) {
  const std::vector<double> same{60, 60, 60};
  const InstanceAverage a = average_over_instances(same);
  EXPECT_NEAR(a.band_low_db, 60, 1e-12);
  EXPECT_NEAR(a.band_high_db, 60, 1e-12);
  const std::vector<double> spread{55, 90};
  const InstanceAverage b = average_over_instances(spread);
  EXPECT_LT(b.band_low_db, b.h_n_db);
  EXPECT_GT(b.band_high_db, b.h_n_db);
  EXPECT_LE(b.band_high_db, kBandFloorDb);
  EXPECT_NE(error_of([] { average_over_instances({}); }), "");
}

TEST(GramLossObjective, ShadowScoresZeroAndTheWindowMaximumIgnoresIt) {
  const std::vector<double> h{54, 108, kInf, 120};
  const auto o = loss_objective(h, 108);
  EXPECT_DOUBLE_EQ(o[0], 0.5);
  EXPECT_DOUBLE_EQ(o[1], 0.0);
  EXPECT_DOUBLE_EQ(o[2], 0.0);
  EXPECT_DOUBLE_EQ(o[3], 0.0);
  EXPECT_EQ(window_maximum(h), 120.0);
  EXPECT_EQ(error_of([&] { loss_objective(h, 0); }),
            "h_max_db = 0 must be a finite number greater than 0");
}

TEST(GramDepthLowpass, StaysWithinTheInputRangeAndLagsDownward) {
  std::vector<double> step(50, 0.0);
  for (std::size_t i = 25; i < step.size(); ++i) step[i] = 1.0;
  const auto y = lowpass_over_depth(step, 10, {});
  EXPECT_DOUBLE_EQ(y[24], 0.0);  // causal: nothing above the step changes
  EXPECT_GT(y[25], 0.0);
  EXPECT_LT(y[25], 1.0);
  for (double v : y) EXPECT_TRUE(v >= 0 && v <= 1);
  const auto z = lowpass_over_depth(step, 10, {1.0 / 50, true});
  EXPECT_GT(z[24], 0.0);  // zero-phase: the step is felt above it too
  EXPECT_EQ(error_of([&] {
              lowpass_over_depth(step, 10, {0, false});
            }),
            "lowpass.cutoff_per_m = 0 must be a finite number greater than 0");
}

TEST(GramSonarEquation, NoDepthAboveTheThresholdGivesAZeroObjective) {
  const std::vector<double> se{-3, -1, -kInf};
  for (double o : signal_excess_objective(se, 0)) EXPECT_EQ(o, 0.0);
  const std::vector<double> some{0, 5, 10};
  const auto o = signal_excess_objective(some, 0);
  EXPECT_DOUBLE_EQ(o[1], 0.5);
  EXPECT_DOUBLE_EQ(o[2], 1.0);
  SonarOptions bad;
  bad.band = {10, 5, 0.5, 3};
  EXPECT_EQ(
      validate_sonar(bad),
      "sonar.band.f_hi_khz = 5 must be a finite number greater than 10 (sonar.band.f_lo_khz)");
}

const std::vector<double> kDepths{10, 20, 30, 40, 50};

TEST(GramBestDepth, PicksTheHighestObjectiveWithinMinAndMaxDepth) {
  const std::vector<double> o{0.9, 0.2, 0.5, 0.7, 0.3};
  EXPECT_EQ(best_depth(kDepths, o, {0, 100, 0}, 100).depth_m, 10);
  EXPECT_EQ(best_depth(kDepths, o, {15, 100, 0}, 100).depth_m, 40);
  EXPECT_EQ(best_depth(kDepths, o, {15, 35, 0}, 100).depth_m, 30);
}

TEST(GramBestDepth, KeepsTheAltitudeAboveTheBottom) {
  const std::vector<double> o{0.1, 0.2, 0.3, 0.4, 0.9};
  const BestDepth b = best_depth(kDepths, o, {0, 100, 12}, 55);
  EXPECT_EQ(b.depth_m, 40);  // 50 m is 5 m off a 55-m bottom
  EXPECT_DOUBLE_EQ(b.deepest_allowed_m, 43);
}

TEST(GramBestDepth, TiesGoToTheShallowestDepth) {
  const std::vector<double> o{0.1, 0.6, 0.3, 0.6, 0.6};
  EXPECT_EQ(best_depth(kDepths, o, {0, 100, 0}, 100).depth_m, 20);
  const std::vector<double> reversed_depths{50, 40, 30, 20, 10};
  EXPECT_EQ(best_depth(reversed_depths, o, {0, 100, 0}, 100).depth_m, 10);
}

TEST(GramBestDepth, AnObjectiveZeroEverywhereGivesTheShallowestAllowedDepthWithoutSignal) {
  const std::vector<double> o(5, 0.0);
  const BestDepth b = best_depth(kDepths, o, {25, 100, 0}, 100);
  EXPECT_EQ(b.depth_m, 30);
  EXPECT_FALSE(b.any_signal);
}

TEST(GramBestDepth, LimitsThatExcludeEveryDepthOrContradictAreErrors) {
  const std::vector<double> o(5, 0.5);
  EXPECT_EQ(error_of([&] {
              best_depth(kDepths, o, {60, 100, 0}, 200);
            }),
            "no receiver depth lies within the vehicle's limits [60, 100] m (max_depth_m 100, "
            "bottom 200 m − min_altitude_m 0; grid depths 10 to 50 m)");
  EXPECT_EQ(error_of([&] {
              best_depth(kDepths, o, {30, 20, 0}, 200);
            }),
            "limits.max_depth_m = 20 must be a finite number of at least 30 (limits.min_depth_m)");
  EXPECT_EQ(error_of([&] {
              best_depth(kDepths, o, {0, 20, -1}, 200);
            }),
            "limits.min_altitude_m = -1 must be a finite number of at least 0");
}

TEST(GramBestDepth, TheBottomUnderTheWindowIsItsShallowestPoint) {
  Environment env;
  env.add_sound_speed()->set_depth_m(0);
  env.add_sound_speed()->set_depth_m(100);
  EXPECT_EQ(shallowest_bottom(env, {0, 0, 500}), 100);  // flat: the last SSP depth
  for (auto [r, z] : {std::pair{0.0, 100.0}, {1000.0, 40.0}, {2000.0, 80.0}}) {
    auto* p = env.add_bathymetry();
    p->set_range_m(r);
    p->set_depth_m(z);
  }
  EXPECT_DOUBLE_EQ(bottom_depth_at(env, 500), 70);
  EXPECT_DOUBLE_EQ(bottom_depth_at(env, 5000), 80);  // extended level
  EXPECT_DOUBLE_EQ(shallowest_bottom(env, {0, 500, 1500}), 40);
  EXPECT_DOUBLE_EQ(shallowest_bottom(env, {0, 0, 500}), 70);
}

TEST(GramDepthObjectiveRequest, ValidationNamesTheField) {
  DepthObjectiveRequest r;
  r.limits = {0, 100, 5};
  EXPECT_EQ(validate_depth_objective_request(r), std::nullopt);
  r.h_max_db = -3;
  EXPECT_EQ(validate_depth_objective_request(r),
            "h_max_db = -3 must be a finite number greater than 0");
  r.h_max_db = std::nullopt;  // the window maximum
  r.horizon_s = -1;
  EXPECT_EQ(validate_depth_objective_request(r),
            "horizon_s = -1 must be a finite number greater than 0");
}

TEST(GramDepthObjectiveRequest, InstancesOnDifferentGridsAreRefused) {
  TransmissionLoss other = small_grid();
  other.depth_m = {11, 20, 30};
  const std::vector<TransmissionLoss> two{small_grid(), other};
  Environment env;
  env.add_sound_speed()->set_depth_m(0);
  env.add_sound_speed()->set_depth_m(100);
  DepthObjectiveRequest r;
  r.range_m = 100;
  r.limits = {0, 100, 0};
  EXPECT_EQ(error_of([&] { compute_depth_objective(two, env, r); }),
            "TL instance 1 has a different receiver grid from instance 0");
}

Environment flat_100m() {
  Environment env;
  env.add_sound_speed()->set_depth_m(0);
  env.add_sound_speed()->set_depth_m(100);
  return env;
}

// Uniform TL per depth: depth i has `tl[i]` dB at every range 100..400 m.
TransmissionLoss layered(std::vector<double> depths, std::vector<double> tl) {
  TransmissionLoss out;
  out.range_m = {100, 200, 300, 400};
  out.depth_m = std::move(depths);
  for (double t : tl)
    for (int j = 0; j < 4; ++j) out.tl_db.push_back(t);
  return out;
}

DepthObjectiveRequest request_at(double r0) {
  DepthObjectiveRequest r;
  r.range_m = r0;
  r.speed_mps = 1;
  r.horizon_s = 150;
  r.limits = {0, 100, 0};
  return r;
}

TEST(GramDepthObjectivePipeline, TheWindowMaximumScoresTheWorstDepthZero) {
  const std::vector<TransmissionLoss> tl{layered({10, 20, 30}, {40, 80, 60})};
  DepthObjectiveRequest req = request_at(100);
  req.h_max_db = std::nullopt;
  const auto r = compute_depth_objective(tl, flat_100m(), req);
  EXPECT_DOUBLE_EQ(r.h_max_db, 80);
  EXPECT_DOUBLE_EQ(r.objective[0], 0.5);
  EXPECT_DOUBLE_EQ(r.objective[1], 0.0);
  EXPECT_DOUBLE_EQ(r.objective[2], 0.25);
  EXPECT_EQ(r.best.depth_m, 10);
}

TEST(GramDepthObjectivePipeline, InstancesAreAveragedInIntensityBeforeTheObjective) {
  const std::vector<TransmissionLoss> tl{layered({10, 20}, {60, 60}), layered({10, 20}, {60, 80})};
  const auto r = compute_depth_objective(tl, flat_100m(), request_at(100));
  EXPECT_NEAR(r.h_bar_db[0], 60, 1e-12);
  EXPECT_NEAR(r.h_bar_db[1], -10 * std::log10((1e-6 + 1e-8) / 2), 1e-12);
  EXPECT_NEAR(r.band_low_db[0], 60, 1e-12);
  EXPECT_LT(r.band_low_db[1], r.h_bar_db[1]);
  EXPECT_GT(r.band_high_db[1], r.h_bar_db[1]);
}

TEST(GramDepthObjectivePipeline, WithSonarOptionsTheSignalExcessObjectiveIsUsed) {
  const std::vector<TransmissionLoss> tl{layered({10, 20, 30}, {60, 70, 90})};
  DepthObjectiveRequest req = request_at(100);
  req.sonar = SonarOptions{};
  req.sonar->source_level_db = 170;
  req.sonar->noise_level_db = 90;
  req.sonar->array_gain_db = 0;
  req.sonar->threshold_db = 10;
  const auto r = compute_depth_objective(tl, flat_100m(), req);
  ASSERT_EQ(r.signal_excess_db.size(), 3u);
  EXPECT_NEAR(r.signal_excess_db[0], 20, 1e-9);  // 170 − 60 − 90 + 0
  EXPECT_NEAR(r.signal_excess_db[2], -10, 1e-9);
  EXPECT_NEAR(r.objective[0], 1.0, 1e-12);
  EXPECT_NEAR(r.objective[1], 0.0, 1e-12);  // SE 10 = the threshold
  EXPECT_EQ(r.objective[2], 0.0);
  EXPECT_EQ(r.best.depth_m, 10);
}

// The site's corrections (gram/site_correction.h) in the sonar equation:
// the excess loss adds to H at every depth, the own-ship noise to NL
// (powers sum), so 90 dB ambient + 90 dB own-ship is 93.01 dB.
TEST(GramDepthObjectivePipeline, TheSitesExcessLossAndOwnShipNoiseLowerTheSignalExcess) {
  const std::vector<TransmissionLoss> tl{layered({10, 20, 30}, {60, 70, 90})};
  DepthObjectiveRequest req = request_at(100);
  req.sonar = SonarOptions{};
  req.sonar->source_level_db = 170;
  req.sonar->noise_level_db = 90;
  req.sonar->threshold_db = 0;
  req.sonar->site.excess_loss_db = 4;
  req.sonar->site.own_ship_noise_db = 90;
  const auto r = compute_depth_objective(tl, flat_100m(), req);
  const double nl = 90 + 10 * std::log10(2.0);
  ASSERT_EQ(r.signal_excess_db.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(r.noise_level_db[i], nl, 1e-9) << i;
  EXPECT_NEAR(r.signal_excess_db[0], 170 - 64 - nl, 1e-9);
  EXPECT_NEAR(r.signal_excess_db[1], 170 - 74 - nl, 1e-9);
  req.sonar->site.excess_loss_db = NAN;
  EXPECT_EQ(validate_sonar(*req.sonar), "sonar.excess_loss_db = nan must be a finite number");
}

TEST(GramDepthObjectivePipeline, TheLowpassStartsAtTheShallowestAllowedDepth) {
  const std::vector<TransmissionLoss> tl{layered({10, 20, 30, 40}, {90, 30, 60, 60})};
  DepthObjectiveRequest req = request_at(100);
  req.limits = {15, 100, 0};
  req.lowpass = LowpassOptions{};
  const auto r = compute_depth_objective(tl, flat_100m(), req);
  EXPECT_EQ(r.objective_filtered[0], r.objective[0]);  // above the limit: raw
  EXPECT_EQ(r.objective_filtered[1], r.objective[1]);  // the filter's first sample
  EXPECT_GT(r.objective_filtered[2], r.objective[2]);  // lags the fall below 20 m
}

TEST(GramDepthObjectivePipeline, UnevenDepthsAreResampledToTenMetresBeforeTheLowpass) {
  // O = {0, 1, 1} at {0, 10, 30} m: on the 10-m grid {0, 1, 1, 1}.
  const std::vector<TransmissionLoss> tl{layered({0, 10, 30}, {100, 0, 0})};
  DepthObjectiveRequest req = request_at(100);
  req.h_max_db = 100;
  req.lowpass = LowpassOptions{};
  const auto r = compute_depth_objective(tl, flat_100m(), req);
  const double a = 1 - std::exp(-2 * M_PI * 10 / 50.0);
  EXPECT_DOUBLE_EQ(r.objective_filtered[0], 0);
  EXPECT_NEAR(r.objective_filtered[1], a, 1e-12);
  EXPECT_NEAR(r.objective_filtered[2], 1 - std::pow(1 - a, 3), 1e-12);
}

TEST(GramDepthLowpass, ACoarseGridIsFilteredOnTenMetreStepsNotPassedThrough) {
  // At 50-m steps a = 1 − e^(−2π) ≈ 0.998: filtering directly would do nothing.
  const std::vector<double> depths{0, 50, 100}, o{0, 1, 1};
  const auto y = lowpass_on_depths(depths, o, {});
  EXPECT_LT(y[1], 0.95);
  EXPECT_GT(y[1], 0.5);
  EXPECT_GT(y[2], y[1]);
  const std::vector<double> repeated{0, 50, 50};
  EXPECT_EQ(error_of([&] { lowpass_on_depths(repeated, o, {}); }),
            "the low-pass needs increasing depths: depth 50 m follows 50 m");
}

Environment munk_like() {
  Environment env;
  for (auto [z, c] : {std::pair{0.0, 1548.0}, {1300.0, 1500.0}, {5000.0, 1551.0}}) {
    auto* p = env.add_sound_speed();
    p->set_depth_m(z);
    p->set_speed_mps(c);
  }
  return env;
}

TEST(GramNoiseDepthProfile, TheCriticalDepthIsWhereTheSpeedAboveTheAxisIsRegained) {
  const auto dc = critical_depth(munk_like());
  ASSERT_TRUE(dc);
  EXPECT_NEAR(*dc, 1300 + 3700 * 48.0 / 51.0, 1e-9);
  EXPECT_DOUBLE_EQ(noise_level_at_depth(60, 1000, dc, 3), 60);
  EXPECT_NEAR(noise_level_at_depth(60, *dc + 1000, dc, 3), 57, 1e-12);
}

TEST(GramNoiseDepthProfile, ShallowOrIsovelocityWaterHasNoCriticalDepth) {
  Environment env = munk_like();
  env.mutable_sound_speed(2)->set_speed_mps(1540);  // never regains 1548
  EXPECT_EQ(critical_depth(env), std::nullopt);
  EXPECT_EQ(critical_depth(flat_100m()), std::nullopt);  // speeds all 0: no channel
  Environment iso = munk_like();
  for (auto& p : *iso.mutable_sound_speed()) p.set_speed_mps(1500);
  EXPECT_EQ(critical_depth(iso), std::nullopt);
  EXPECT_DOUBLE_EQ(noise_level_at_depth(60, 4000, std::nullopt, 3), 60);
}

TEST(GramDepthObjectivePipeline, BelowTheCriticalDepthTheNoiseFallsAndTheSignalExcessRises) {
  const std::vector<TransmissionLoss> tl{layered({1000, 4882.35294117647, 5000}, {80, 80, 80})};
  DepthObjectiveRequest req = request_at(100);
  req.limits = {0, 6000, 0};
  req.sonar = SonarOptions{};
  req.sonar->source_level_db = 180;
  req.sonar->noise_level_db = 70;
  req.sonar->noise_decrease_db_per_km = 3;
  const auto r = compute_depth_objective(tl, munk_like(), req);
  ASSERT_TRUE(r.critical_depth_m);
  EXPECT_DOUBLE_EQ(r.noise_level_db[0], 70);
  EXPECT_NEAR(r.noise_level_db[1], 70 - 0.3, 1e-9);  // 100 m below d_c
  EXPECT_NEAR(r.signal_excess_db[1], 30.3, 1e-9);
  EXPECT_EQ(r.best.depth_m, 5000);
}

// Its time is measured by tests/bench/depth_objective_bench.cpp.
TEST(GramDepthObjectiveEndToEnd, ThePekerisModelRunGivesABestDepthInsideTheLimits) {
  // The case is stated once (tests/support/pekeris_depth_case.h), with the bench.
  const Environment env = test::pekeris_depth_case_environment(ACOMMS_SHARED_DIR);
  const std::vector<TransmissionLoss> tl{compute_transmission_loss(env)};
  const DepthObjectiveRequest req = test::pekeris_depth_case_request();
  const DepthObjectiveResult r = compute_depth_objective(tl, env, req);
  EXPECT_EQ(r.ranges_in_window, 8u);
  EXPECT_EQ(r.depth_m.size(), 25u);
  EXPECT_EQ(r.bottom_m, 100);
  ASSERT_TRUE(r.best.any_signal);
  EXPECT_GE(r.best.depth_m, 5);
  EXPECT_LE(r.best.depth_m, 90);
  for (std::size_t i = 0; i < r.depth_m.size(); ++i) {
    EXPECT_TRUE(std::isfinite(r.h_bar_db[i])) << r.depth_m[i];
    EXPECT_NEAR(r.objective[i], std::max(1 - r.h_bar_db[i] / 70, 0.0), 1e-12);
    if (r.depth_m[i] >= 5 && r.depth_m[i] <= 90) {
      EXPECT_LE(r.objective_filtered[i], r.best.objective + kObjectiveTie) << r.depth_m[i];
    }
  }
}

}  // namespace
}  // namespace acomms::gram
