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

}  // namespace
}  // namespace acomms::gram
