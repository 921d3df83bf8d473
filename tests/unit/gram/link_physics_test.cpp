// The pieces that judge a simulated packet: the reception curve, TL at any
// point of a grid, the sea state's wind and the noise level from them.
#include <gtest/gtest.h>

#include <cmath>

#include "gram/ambient_noise.h"
#include "gram/link_physics.h"
#include "gram/reception_curve.h"
#include "gram/sea_state.h"
#include "gram/tl_lookup.h"

namespace acomms::gram {
namespace {

TEST(ReceptionCurve, DefaultsAreHalfAtTenDbForFskAndFourteenForPskWithUnitSlope) {
  EXPECT_DOUBLE_EQ(reception_probability(default_reception_curve(0), 10.0), 0.5);
  for (int rate = 1; rate <= 5; ++rate) EXPECT_DOUBLE_EQ(reception_probability(default_reception_curve(rate), 14.0), 0.5);
  // Logistic with k = 1/dB: one dB above the midpoint is 1 / (1 + e^-1).
  EXPECT_NEAR(reception_probability(default_reception_curve(0), 11.0), 1.0 / (1.0 + std::exp(-1.0)), 1e-15);
  EXPECT_NEAR(reception_probability(default_reception_curve(3), 12.0), 1.0 / (1.0 + std::exp(2.0)), 1e-15);
}

TEST(ReceptionCurve, NoPathNeverDecodesAndAHugeSnrAlwaysDoes) {
  const ReceptionCurve c = default_reception_curve(0);
  EXPECT_EQ(reception_probability(c, -INFINITY), 0.0);
  EXPECT_EQ(reception_probability(c, NAN), 0.0);
  EXPECT_EQ(reception_probability(c, INFINITY), 1.0);
  EXPECT_EQ(reception_probability(c, -1e6), 0.0);
}

TEST(ReceptionCurve, ValidationNamesTheFieldAndTheBound) {
  auto problem = validate_reception_curve({10, 0}, "physics.reception[0].");
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("physics.reception[0].slope_per_db must be in (0, 100]"), std::string::npos) << *problem;
  problem = validate_reception_curve({NAN, 1}, "x.");
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("x.snr50_db"), std::string::npos);
  EXPECT_FALSE(validate_reception_curve({10, 1}, ""));
}

TEST(SeaState, FollowsTheSpecsBeaufortTableAndRefusesAGale) {
  EXPECT_EQ(wind_speed_for_sea_state(2), 2.5);
  EXPECT_EQ(wind_speed_for_sea_state(3), 4.5);
  EXPECT_EQ(wind_speed_for_sea_state(4), 7.0);
  EXPECT_FALSE(wind_speed_for_sea_state(-1));
  EXPECT_FALSE(wind_speed_for_sea_state(7));
}

TEST(LinkPhysics, NoiseModelIsTheBandLevelAroundTheCarrier) {
  NoiseModelInput in;  // sea state 2, 25 kHz ± 2080 Hz, shipping 0.5
  EXPECT_NEAR(modelled_noise_level_db(in), ambient_noise_band_level(22.92, 27.08, 0.5, 2.5), 1e-9);
  in.sea_state = 9;
  try {
    modelled_noise_level_db(in, "physics.noise_model.");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("physics.noise_model.sea_state must be in 0..6"), std::string::npos);
  }
}

TEST(LinkPhysics, DefaultBandIsTheMicroModemsFractionOfTheCarrier) {
  EXPECT_DOUBLE_EQ(default_band_hz(25000), 4160);
  EXPECT_DOUBLE_EQ(default_band_hz(500), 83.2);
  NoiseModelInput low;
  low.centre_hz = 500;
  low.band_hz = default_band_hz(500);
  EXPECT_TRUE(std::isfinite(modelled_noise_level_db(low)));
}

TEST(LinkPhysics, DefaultDepthStepIsTwoMetresOrAHundredthOfDeepWater) {
  EXPECT_EQ(default_depth_step_m(110), 2.0);
  EXPECT_EQ(default_depth_step_m(5000), 50.0);
}

TEST(LinkPhysics, SnrIsSourceLevelLessLossLessNoise) {
  LinkPhysics p;
  p.noise_level_db = 70;
  const LinkOutcome o = link_outcome(p, 110.0, 0);  // 190 − 110 − 70 = 10 dB: the FSK midpoint
  EXPECT_DOUBLE_EQ(o.snr_db, 10.0);
  EXPECT_DOUBLE_EQ(o.probability, 0.5);
  EXPECT_DOUBLE_EQ(link_outcome(p, 106.0, 1).probability, 0.5);  // PSK: 14 dB
  EXPECT_DOUBLE_EQ(link_outcome(p, 106.0, -1).probability, reception_probability(default_reception_curve(0), 14.0));
  p.curves[0] = {20, 2};
  EXPECT_DOUBLE_EQ(link_outcome(p, 100.0, 0).probability, 0.5);
  const LinkOutcome shadow = link_outcome(p, INFINITY, 0);
  EXPECT_EQ(shadow.snr_db, -INFINITY);
  EXPECT_EQ(shadow.probability, 0.0);
}

// Powers add: equal levels give +3.01 dB; a level 30 dB below another adds
// 0.004 dB; nothing (−inf) adds nothing; no overflow at high levels.
TEST(SiteCorrection, NoiseLevelsAddAsPowers) {
  EXPECT_NEAR(power_sum_db(70, 70), 70 + 10 * std::log10(2.0), 1e-12);
  EXPECT_NEAR(power_sum_db(100, 70), 100 + 10 * std::log10(1.001), 1e-12);
  EXPECT_NEAR(power_sum_db(70, 100), power_sum_db(100, 70), 1e-12);
  EXPECT_EQ(power_sum_db(80, -INFINITY), 80);
  EXPECT_NEAR(power_sum_db(4000, 4000), 4000 + 10 * std::log10(2.0), 1e-9);
  SiteCorrection none;
  EXPECT_EQ(none.total_noise_db(66), 66);
}

TEST(SiteCorrection, ExcessLossAndOwnShipNoiseLowerTheSnr) {
  LinkPhysics p;
  p.noise_level_db = 70;
  p.site.excess_loss_db = 6;
  const LinkOutcome lossy = link_outcome(p, 104.0, 0);  // 190 − (104 + 6) − 70 = 10 dB
  EXPECT_DOUBLE_EQ(lossy.tl_db, 104.0) << "the model's TL, reported without the site's excess";
  EXPECT_DOUBLE_EQ(lossy.snr_db, 10.0);
  EXPECT_DOUBLE_EQ(lossy.probability, 0.5);
  p.site.excess_loss_db = -3;  // a calibration may find the model pessimistic
  EXPECT_DOUBLE_EQ(link_outcome(p, 104.0, 0).snr_db, 19.0);
  p.site.excess_loss_db = 0;
  p.site.own_ship_noise_db = 70;
  EXPECT_NEAR(link_outcome(p, 110.0, 0).snr_db, 10 - 10 * std::log10(2.0), 1e-12);
  EXPECT_EQ(validate_site_correction(p.site, "x."), std::nullopt);
  p.site.own_ship_noise_db = INFINITY;
  EXPECT_EQ(validate_site_correction(p.site, "x."), "x.own_ship_noise_db = inf must be a finite number");
}

TransmissionLoss two_by_three() {
  TransmissionLoss tl;
  tl.range_m = {0, 100, 200};
  tl.depth_m = {10, 20};
  tl.tl_db = {NAN, 40, 50,  //
              NAN, 60, INFINITY};
  return tl;
}

TEST(TlLookup, OnAReceiverItIsThatReceiversLoss) {
  const TransmissionLoss tl = two_by_three();
  EXPECT_NEAR(tl_at(tl, 100, 10), 40, 1e-12);
  EXPECT_NEAR(tl_at(tl, 200, 10), 50, 1e-12);
  EXPECT_NEAR(tl_at(tl, 100, 20), 60, 1e-12);
}

TEST(TlLookup, InterpolatesInIntensityNotInDecibels) {
  const TransmissionLoss tl = two_by_three();
  // Halfway between 40 and 50 dB: the mean intensity, 42.6 dB, not 45.
  EXPECT_NEAR(tl_at(tl, 150, 10), -10 * std::log10((1e-4 + 1e-5) / 2), 1e-9);
  // A shadow corner counts as silence, it does not silence the cell.
  EXPECT_NEAR(tl_at(tl, 150, 20), -10 * std::log10(1e-6 / 2), 1e-9);
  EXPECT_EQ(tl_at(tl, 200, 20), INFINITY);
}

TEST(TlLookup, ClampsOutsideTheGridAndSkipsTheSourceAxis) {
  const TransmissionLoss tl = two_by_three();
  EXPECT_NEAR(tl_at(tl, 0, 10), 40, 1e-12);   // range 0 has no value: the first positive range
  EXPECT_NEAR(tl_at(tl, 50, 10), 40, 1e-12);
  EXPECT_NEAR(tl_at(tl, 900, 10), 50, 1e-12);
  EXPECT_NEAR(tl_at(tl, 100, 0), 40, 1e-12);
  EXPECT_NEAR(tl_at(tl, 100, 99), 60, 1e-12);
  TransmissionLoss irregular = tl;
  irregular.irregular = true;
  EXPECT_THROW(tl_at(irregular, 100, 10), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::gram
