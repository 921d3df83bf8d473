// The depth-objective query on the wire: what proto3 cannot say (unset
// scalars, an unset choice) is refused with the field's name.
#include "gram/depth_objective_proto.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace acomms::gram {
namespace {

DepthObjectiveQuery good_query() {
  DepthObjectiveQuery q;
  q.set_range_m(2000);
  q.set_speed_mps(1.5);
  q.set_heading_deg(30);
  q.set_horizon_s(120);
  q.set_h_max_db(108);
  q.mutable_limits()->set_min_depth_m(5);
  q.mutable_limits()->set_max_depth_m(200);
  q.mutable_limits()->set_min_altitude_m(10);
  return q;
}

std::string error_of(const DepthObjectiveQuery& q) {
  try {
    request_from_proto(q);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(GramDepthObjectiveProto, AGoodQueryCarriesEveryField) {
  DepthObjectiveQuery q = good_query();
  q.mutable_lowpass()->set_cutoff_per_m(0.02);
  q.mutable_lowpass()->set_zero_phase(true);
  const DepthObjectiveRequest r = request_from_proto(q);
  EXPECT_EQ(r.range_m, 2000);
  EXPECT_EQ(r.speed_mps, 1.5);
  EXPECT_EQ(r.heading_deg, 30);
  EXPECT_EQ(r.horizon_s, 120);
  EXPECT_EQ(r.h_max_db, 108.0);
  EXPECT_EQ(r.limits.min_altitude_m, 10);
  ASSERT_TRUE(r.lowpass);
  EXPECT_TRUE(r.lowpass->zero_phase);
  EXPECT_FALSE(r.sonar);
}

TEST(GramDepthObjectiveProto, AnUnsetHorizonIsRefusedNotRunAsZero) {
  DepthObjectiveQuery q = good_query();
  q.clear_horizon_s();
  EXPECT_EQ(error_of(q), "horizon_s = 0 must be a finite number greater than 0");
}

TEST(GramDepthObjectiveProto, HmaxMustBeChosen) {
  DepthObjectiveQuery q = good_query();
  q.clear_h_max();
  EXPECT_EQ(error_of(q),
            "h_max is not set: give h_max_db (e.g. 108) or h_max_window_maximum = true");
  q.set_h_max_window_maximum(true);
  EXPECT_EQ(request_from_proto(q).h_max_db, std::nullopt);
}

TEST(GramDepthObjectiveProto, MissingLimitsAndSonarNoiseAreNamed) {
  DepthObjectiveQuery q = good_query();
  q.clear_limits();
  EXPECT_EQ(error_of(q), "limits is not set: give min_depth_m, max_depth_m, min_altitude_m");
  q = good_query();
  q.mutable_sonar()->set_source_level_db(185);
  EXPECT_EQ(error_of(q), "sonar.noise is not set: give noise_level_db or noise_band");
  q.mutable_sonar()->mutable_noise_band()->set_f_lo_khz(9);
  q.mutable_sonar()->mutable_noise_band()->set_f_hi_khz(14);
  q.mutable_sonar()->mutable_noise_band()->set_shipping(2);
  EXPECT_EQ(error_of(q), "sonar.band.shipping = 2 must be at most 1");
}

TEST(GramDepthObjectiveProto, SonarOptionsCarryTheNoiseChoiceAndItsDepthDecrease) {
  DepthObjectiveQuery q = good_query();
  q.mutable_sonar()->set_source_level_db(185);
  q.mutable_sonar()->set_noise_level_db(80);
  DepthObjectiveRequest r = request_from_proto(q);
  ASSERT_TRUE(r.sonar);
  EXPECT_EQ(r.sonar->noise_level_db, 80.0);
  EXPECT_EQ(r.sonar->noise_decrease_db_per_km, std::nullopt);
  q.mutable_sonar()->set_noise_decrease_db_per_km(3);
  EXPECT_EQ(request_from_proto(q).sonar->noise_decrease_db_per_km, 3.0);
  q.mutable_sonar()->set_noise_decrease_db_per_km(-1);
  EXPECT_EQ(error_of(q),
            "sonar.noise_decrease_db_per_km = -1 must be a finite number of at least 0");
}

TEST(GramDepthObjectiveProto, TheReplyListsEveryDepth) {
  DepthObjectiveResult r;
  r.window = {180, 2000, 2180, false, false};
  r.ranges_in_window = 8;
  r.depth_m = {10, 20};
  r.h_bar_db = {60, 70};
  r.band_low_db = {59, 69};
  r.band_high_db = {61, 71};
  r.objective = {0.4, 0.3};
  r.objective_filtered = {0.4, 0.35};
  r.best = {0, 10, 0.4, true, 90};
  const DepthObjectiveReply a = reply_to_proto(r);
  EXPECT_EQ(a.window_end_m(), 2180);
  EXPECT_EQ(a.ranges_in_window(), 8u);
  EXPECT_EQ(a.best_depth_m(), 10);
  EXPECT_TRUE(a.any_signal());
  ASSERT_EQ(a.points_size(), 2);
  EXPECT_EQ(a.points(1).objective_filtered(), 0.35);
}

TEST(GramDepthObjectiveProto, AForecastQueryCarriesItsFieldsAndAnUnsetVerticalSpeedIsRefused) {
  DepthObjectiveQuery q = good_query();
  EXPECT_FALSE(request_from_proto(q).forecast);
  q.mutable_forecast()->set_forecast_horizon_s(3600);
  q.mutable_forecast()->set_current_depth_m(40);
  q.mutable_forecast()->set_caustic_uncertainty_m(50);
  EXPECT_EQ(error_of(q), "vertical_speed_mps = 0 must be a finite number greater than 0");
  q.mutable_forecast()->set_vertical_speed_mps(0.5);
  const DepthObjectiveRequest r = request_from_proto(q);
  ASSERT_TRUE(r.forecast);
  EXPECT_EQ(r.forecast->forecast_horizon_s, 3600);
  EXPECT_EQ(r.forecast->current_depth_m, 40);
  EXPECT_EQ(r.forecast->options.vertical_speed_mps, 0.5);
  EXPECT_EQ(r.forecast->caustic_uncertainty_m, 50);
  EXPECT_FALSE(r.forecast->leg_end_range_m);
  q.mutable_forecast()->set_leg_end_range_m(60000);
  EXPECT_EQ(request_from_proto(q).forecast->leg_end_range_m, 60000);
  EXPECT_FALSE(request_from_proto(q).forecast->reception);
  q.mutable_forecast()->set_reception_snr50_db(12);  // the slope left 0: 1/dB
  // The curve is read at the sonar equation's signal excess: without it
  // the curve would be silently ignored, so it is refused.
  EXPECT_EQ(error_of(q),
            "reception_snr50_db needs the sonar equation (sonar): the reception curve is read at its signal excess");
  q.mutable_sonar()->set_source_level_db(185);
  q.mutable_sonar()->set_noise_level_db(80);
  ASSERT_TRUE(request_from_proto(q).forecast->reception);
  EXPECT_EQ(request_from_proto(q).forecast->reception->snr50_db, 12);
  EXPECT_EQ(request_from_proto(q).forecast->reception->slope_per_db, 1);
  q.mutable_forecast()->set_reception_slope_per_db(0.5);
  EXPECT_EQ(request_from_proto(q).forecast->reception->slope_per_db, 0.5);
  q.mutable_forecast()->set_reception_slope_per_db(-1);
  EXPECT_NE(error_of(q).find("reception_slope_per_db"), std::string::npos);
  q.mutable_forecast()->clear_reception_snr50_db();
  // A slope without the curve's SNR50 would be neither applied nor checked.
  EXPECT_EQ(error_of(q),
            "reception_slope_per_db is set without reception_snr50_db: give the curve's SNR50 too, or neither");
  q.mutable_forecast()->set_reception_slope_per_db(0.5);
  EXPECT_EQ(error_of(q),
            "reception_slope_per_db is set without reception_snr50_db: give the curve's SNR50 too, or neither");
  q.mutable_forecast()->clear_reception_slope_per_db();
  q.clear_sonar();
  q.mutable_forecast()->set_forecast_horizon_s(121 * 120);  // more columns than a query may ask
  EXPECT_NE(error_of(q).find("must be at most 120 times horizon_s"), std::string::npos);
  q.mutable_forecast()->set_forecast_horizon_s(60);  // shorter than one window
  EXPECT_NE(error_of(q).find("forecast_horizon_s = 60 must be at least horizon_s = 120"), std::string::npos);
}

TEST(GramDepthObjectiveProto, TheReplyCarriesTheForecast) {
  DepthObjectiveResult r;
  r.window = {180, 2000, 2180, false, false};
  r.depth_m = {10, 20};
  r.h_bar_db = {60, 70};
  r.band_low_db = r.band_high_db = r.h_bar_db;
  r.objective = r.objective_filtered = {0.4, 0.3};
  r.best = {0, 10, 0.4, true, 90};
  DepthForecastResult f;
  f.field.depth_m = r.depth_m;
  f.field.time_s = {0, 120};
  f.field.steer = {{0.4, 0.3}, {0.2, 0.5}};
  f.windows = {r.window, {180, 2180, 2360, false, false}};
  f.horizon_used_s = 120;
  f.decision.choice = ForecastChoice::kOptimum;
  f.decision.target_depth_m = 20;
  f.decision.target_time_s = 120;
  f.decision.target_objective = 0.5;
  f.decision.vertical_rate_mps = 10.0 / 120;
  f.decision.path_time_s = {0, 120};
  f.decision.path_depth_m = {10, 20};
  f.decision.expected_score = 0.4;
  f.next_depth_m = 20;
  r.forecast = f;
  const DepthObjectiveReply a = reply_to_proto(r);
  ASSERT_TRUE(a.has_forecast());
  EXPECT_EQ(a.forecast().choice(), "optimum");
  EXPECT_EQ(a.forecast().target_depth_m(), 20);
  EXPECT_EQ(a.forecast().next_depth_m(), 20);
  ASSERT_EQ(a.forecast().columns_size(), 2);
  EXPECT_EQ(a.forecast().columns(1).window_begin_m(), 2180);
  EXPECT_EQ(a.forecast().columns(1).objective(1), 0.5);
  ASSERT_EQ(a.forecast().path_depth_m_size(), 2);
  EXPECT_EQ(a.forecast().path_depth_m(1), 20);
  EXPECT_EQ(a.forecast().expected_score(), 0.4);
}

}  // namespace
}  // namespace acomms::gram
