// The link calibration's fit (eval/link_calibration.h) on data with known
// answers: exact ones where the maximum-likelihood answer is known in
// closed form, planted ones drawn from a seeded generator, and the
// refusals when the data cannot carry a fit.
#include "eval/link_calibration.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "acomms/v1/config.pb.h"

namespace acomms::eval {
namespace {

PacketSample packet(double predicted, bool decoded, std::optional<double> measured = std::nullopt, int32_t src = 1,
                    int32_t rate = 0) {
  PacketSample s;
  s.src = src;
  s.rate = rate;
  s.decoded = decoded;
  s.predicted_snr_db = predicted;
  s.measured_snr_db = measured;
  return s;
}

// Two predicted SNRs, 9 and 11 dB, with 1/4 and 3/4 decoded: the
// maximum-likelihood curve goes through both proportions exactly, so its
// 50% point is 10 dB and its slope ln(3)/1 dB.
TEST(LinkCalibrationFit, TwoLevelDesignGivesTheClosedFormCurve) {
  std::vector<PacketSample> samples;
  for (int i = 0; i < 40; ++i) samples.push_back(packet(9, i % 4 == 0));
  for (int i = 0; i < 40; ++i) samples.push_back(packet(11, i % 4 != 0));
  std::string why;
  const std::optional<ReceptionFit> fit = fit_reception_curve(samples, &why);
  ASSERT_TRUE(fit) << why;
  EXPECT_NEAR(fit->snr50_predicted_db, 10.0, 1e-9);
  EXPECT_NEAR(fit->slope_per_db, std::log(3.0), 1e-9);
  EXPECT_EQ(fit->packets, 80u);
  EXPECT_EQ(fit->decoded, 40u);
  // Fisher information at the fit: x = ±1 about the mean, p(1−p) = 3/16
  // on all 80, so var(b) = 1/(80·3/16) = 1/15 and var(x50) = var(a)/b² =
  // (1/15)/ln(3)².
  EXPECT_NEAR(fit->slope_ci95_per_db, 1.959964 * std::sqrt(1.0 / 15), 1e-6);
  EXPECT_NEAR(fit->snr50_ci95_db, 1.959964 * std::sqrt(1.0 / 15) / std::log(3.0), 1e-6);
}

TEST(LinkCalibrationFit, ExcessLossIsPredictedLessMeasuredWithItsSpread) {
  // Offsets −5, −6, −7 repeated: mean −6, sample standard deviation known.
  std::vector<PacketSample> samples;
  for (int i = 0; i < 30; ++i) samples.push_back(packet(20, true, 20 - 6 + (i % 3 - 1)));
  samples.push_back(packet(5, false));  // lost: no measured SNR, not counted
  std::string why;
  const std::optional<ExcessLossFit> fit = fit_excess_loss(samples, &why);
  ASSERT_TRUE(fit) << why;
  EXPECT_EQ(fit->packets, 30u);
  EXPECT_NEAR(fit->offset_db, -6.0, 1e-12);
  EXPECT_NEAR(fit->excess_loss_db(), 6.0, 1e-12);
  EXPECT_NEAR(fit->spread_db, std::sqrt(20.0 / 29.0), 1e-12);
  EXPECT_NEAR(fit->offset_ci95_db, 1.959964 * std::sqrt(20.0 / 29.0) / std::sqrt(30.0), 1e-5);
}

TEST(LinkCalibrationFit, PlantedCurveAndExcessLossAreRecoveredFromNoisyDraws) {
  constexpr double kExcess = 7.5, kScatter = 2.0, kSnr50 = 12.0, kSlope = 0.6;
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> predicted(5, 40);
  std::normal_distribution<double> scatter(0, kScatter);
  std::uniform_real_distribution<double> draw(0, 1);
  std::vector<PacketSample> samples;
  for (int i = 0; i < 3000; ++i) {
    const double x = predicted(rng);
    // The site: the true SNR is the prediction less the excess loss; the
    // modem decodes by its curve on the true SNR and measures it with scatter.
    const double truth = x - kExcess;
    const bool decoded = draw(rng) < 1 / (1 + std::exp(-kSlope * (truth - kSnr50)));
    samples.push_back(packet(x, decoded, decoded ? std::optional(truth + scatter(rng)) : std::nullopt));
  }
  const std::vector<LinkCalibration> links = calibrate_links(samples);
  ASSERT_EQ(links.size(), 1u);
  const LinkCalibration& link = links[0];
  ASSERT_TRUE(link.excess) << link.excess_refused;
  EXPECT_NEAR(link.excess->excess_loss_db(), kExcess, 0.2);
  EXPECT_NEAR(link.excess->spread_db, kScatter, 0.15);
  const RateCalibration& rate = link.rates.at(0);
  ASSERT_TRUE(rate.curve) << rate.curve_refused;
  // Against the predicted SNR the 50% point sits the excess loss higher.
  EXPECT_NEAR(rate.curve->snr50_predicted_db, kSnr50 + kExcess, 0.5);
  EXPECT_NEAR(link.physics_snr50_db(*rate.curve), kSnr50, 0.5);
  EXPECT_NEAR(rate.curve->slope_per_db, kSlope, 0.1);
  // The intervals are honest: the truth is inside (this seed), and narrow.
  EXPECT_LT(std::abs(rate.curve->snr50_predicted_db - (kSnr50 + kExcess)), rate.curve->snr50_ci95_db * 1.5);
  EXPECT_LT(rate.curve->snr50_ci95_db, 0.5);
  EXPECT_LT(std::abs(rate.curve->slope_per_db - kSlope), rate.curve->slope_ci95_per_db * 1.5);
}

TEST(LinkCalibrationFit, TooFewPacketsAreRefusedNamingTheCountAndTheBound) {
  std::vector<PacketSample> samples;
  for (int i = 0; i < 29; ++i) samples.push_back(packet(i, i > 14, i > 14 ? std::optional(i - 3.0) : std::nullopt));
  std::string why;
  EXPECT_FALSE(fit_reception_curve(samples, &why));
  EXPECT_EQ(why, "too few packets to fit a reception curve: 29, at least 30 needed");
  samples.resize(9 + 15);  // 9 decoded with a measured SNR
  samples.erase(samples.begin(), samples.begin() + 15);
  EXPECT_FALSE(fit_excess_loss(samples, &why));
  EXPECT_EQ(why, "too few decoded packets with a measured SNR to fit an excess loss: 9, at least 10 needed");
}

TEST(LinkCalibrationFit, DataThatDoNotSpanTheThresholdAreRefused) {
  std::vector<PacketSample> samples;
  for (int i = 0; i < 40; ++i) samples.push_back(packet(20 + i * 0.1, i != 7));  // one lost in 40
  std::string why;
  EXPECT_FALSE(fit_reception_curve(samples, &why));
  EXPECT_NE(why.find("39 of 40 packets decoded"), std::string::npos) << why;
}

TEST(LinkCalibrationFit, PerfectlySeparatedDataAreRefusedAsAnUnboundedSlope) {
  std::vector<PacketSample> samples;
  for (int i = 0; i < 40; ++i) samples.push_back(packet(i, i >= 20));
  std::string why;
  EXPECT_FALSE(fit_reception_curve(samples, &why));
  EXPECT_NE(why.find("unbounded"), std::string::npos) << why;
}

TEST(LinkCalibrationFit, LinksAndRatesAreFittedApart) {
  std::vector<PacketSample> samples;
  for (int i = 0; i < 40; ++i) {
    samples.push_back(packet(9 + 2 * (i % 2), i % 3 == 0, 0.0, 3, 0));
    samples.push_back(packet(1, true, 1.0, 4, 2));
  }
  const std::vector<LinkCalibration> links = calibrate_links(samples);
  ASSERT_EQ(links.size(), 2u);
  EXPECT_EQ(links[0].src, 3);
  EXPECT_EQ(links[1].src, 4);
  EXPECT_EQ(links[1].rates.count(2), 1u);
  EXPECT_EQ(links[1].rates.count(0), 0u);
  EXPECT_FALSE(links[1].rates.at(2).curve);  // every packet decoded
  ASSERT_TRUE(links[1].excess);
  EXPECT_NEAR(links[1].excess->offset_db, 0.0, 1e-12);
}

TEST(LinkCalibrationEvents, OnlyPacketEventsWithAFinitePredictionAreSamples) {
  std::vector<v1::Event> events(5);
  events[0].set_kind("received");  // a message's event: not a packet
  events[0].mutable_link()->set_predicted_snr_db(3);
  events[1].set_kind("packet");  // no prediction (no environment): skipped
  events[1].mutable_link()->set_snr_in_db(4);
  events[1].mutable_link()->set_decoded(true);
  events[2].set_kind("packet");  // a shadow: −inf predicted, skipped
  events[2].mutable_link()->set_predicted_snr_db(-INFINITY);
  events[3].set_kind("packet");
  events[3].set_src(7);
  events[3].set_time(100);
  events[3].mutable_link()->set_transmission_src(7);
  events[3].mutable_link()->set_rate(1);
  events[3].mutable_link()->set_decoded(true);
  events[3].mutable_link()->set_snr_in_db(8);
  events[3].mutable_link()->set_predicted_snr_db(14);
  events[4].set_kind("packet");
  events[4].set_src(7);
  events[4].mutable_link()->set_decoded(false);
  events[4].mutable_link()->set_predicted_snr_db(2);
  std::size_t skipped = 0;
  const std::vector<PacketSample> samples = packet_samples(events, &skipped);
  EXPECT_EQ(skipped, 2u);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[0].src, 7);
  EXPECT_EQ(samples[0].rate, 1);
  EXPECT_TRUE(samples[0].decoded);
  EXPECT_EQ(samples[0].measured_snr_db, 8.0);
  EXPECT_EQ(samples[0].predicted_snr_db, 14.0);
  EXPECT_EQ(samples[0].time, 100.0);
  EXPECT_FALSE(samples[1].decoded);
  EXPECT_FALSE(samples[1].measured_snr_db);
  EXPECT_EQ(samples[1].src, 7);  // from the event when the figures do not say
}

TEST(LinkCalibrationBlock, ThePhysicsBlockParsesAsTheSimulatorsConfigInItsConvention) {
  // Measured = predicted − 6 exactly; decoded 1/4 at 15 dB, 3/4 at 17 dB
  // predicted: 50% at 16 dB predicted, 10 dB in the corrected SNR.
  std::vector<PacketSample> samples;
  for (int i = 0; i < 40; ++i) {
    const bool low_decoded = i % 4 == 0, high_decoded = i % 4 != 0;
    samples.push_back(packet(15, low_decoded, low_decoded ? std::optional(9.0) : std::nullopt));
    samples.push_back(packet(17, high_decoded, high_decoded ? std::optional(11.0) : std::nullopt));
  }
  const std::vector<LinkCalibration> links = calibrate_links(samples);
  ASSERT_EQ(links.size(), 1u);
  const std::string block = physics_block(links[0]);
  v1::DriverConfig config;
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString("sim { " + block + " }", &config)) << block;
  const drivers::SimPhysicsConfig& physics = config.sim().physics();
  EXPECT_NEAR(physics.excess_loss_db(), 6.0, 0.005);
  ASSERT_EQ(physics.reception_size(), 1);
  EXPECT_EQ(physics.reception(0).rate(), 0);
  EXPECT_NEAR(physics.reception(0).snr50_db(), 10.0, 0.005);
  EXPECT_NEAR(physics.reception(0).slope_per_db(), std::log(3.0), 0.0005);
}

}  // namespace
}  // namespace acomms::eval
