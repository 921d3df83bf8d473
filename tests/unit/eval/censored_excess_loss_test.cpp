// The censored excess-loss fit (eval/censored_excess_loss.h) on synthetic
// scattered data with a planted offset: the decoded-only mean is biased
// upwards near the threshold, the censored fit recovers the offset; and
// calibrate_links takes it, link by link (LinkFigures.link).
#include "eval/censored_excess_loss.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "eval/link_calibration.h"

namespace acomms::eval {
namespace {

constexpr double kOffset = -6;   // measured − predicted, planted
constexpr double kScatter = 3;   // σ of single packets about it
constexpr double kThreshold = 12;

// Packets predicted uniformly over [10, 26] dB: their true SNR p + μ + σε
// spans the threshold. Decoded with probability Φ((s − 12)/width) (width 0:
// a hard threshold); a decoded packet reports its true SNR.
std::vector<PacketSample> scattered(int n, double width, unsigned seed, const std::string& link = "") {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> predicted(10, 26);
  std::normal_distribution<double> normal(0, 1);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::vector<PacketSample> out;
  for (int i = 0; i < n; ++i) {
    PacketSample s;
    s.link = link;
    s.src = 2;
    s.predicted_snr_db = predicted(random);
    const double truth = s.predicted_snr_db + kOffset + kScatter * normal(random);
    const double p = width > 0 ? 0.5 * std::erfc(-(truth - kThreshold) / width / std::sqrt(2.0))
                               : (truth >= kThreshold ? 1.0 : 0.0);
    s.decoded = uniform(random) < p;
    if (s.decoded) s.measured_snr_db = truth;
    out.push_back(s);
  }
  return out;
}

TEST(CensoredExcessLoss, RemovesTheSurvivorsBiasOfScatteredDataNearTheThreshold) {
  const std::vector<PacketSample> samples = scattered(3000, 1.0, 7);
  std::string why;
  const std::optional<ExcessLossFit> naive = fit_excess_loss(samples, &why);
  ASSERT_TRUE(naive) << why;
  // The bias the issue names: the decoded-only mean overstates the offset.
  EXPECT_GT(naive->offset_db - kOffset, 0.6) << "naive " << naive->offset_db;
  EXPECT_GT(std::abs(naive->offset_db - kOffset), 3 * naive->offset_ci95_db);
  const std::optional<CensoredExcessLossFit> fit = fit_censored_excess_loss(samples, &why);
  ASSERT_TRUE(fit) << why;
  std::printf("planted offset %.2f dB, scatter %.2f dB: decoded-only mean %.2f +/- %.2f dB; censored fit %.2f +/- "
              "%.2f dB, spread %.2f dB, threshold %.2f dB, width %.2f dB\n",
              kOffset, kScatter, naive->offset_db, naive->offset_ci95_db, fit->offset_db, fit->offset_ci95_db,
              fit->spread_db, fit->snr50_db, fit->width_db);
  EXPECT_NEAR(fit->offset_db, kOffset, 0.3);
  EXPECT_NEAR(fit->offset_db, kOffset, 2 * fit->offset_ci95_db) << "+/- " << fit->offset_ci95_db;
  EXPECT_NEAR(fit->spread_db, kScatter, 0.3);
  EXPECT_NEAR(fit->snr50_db, kThreshold, 0.5);
  EXPECT_NEAR(fit->width_db, 1.0, 0.6);
  EXPECT_EQ(fit->packets, 3000u);
  EXPECT_EQ(fit->measured, naive->packets);
}

TEST(CensoredExcessLoss, AHardThresholdIsTheTobitLimit) {
  const std::vector<PacketSample> samples = scattered(3000, 0, 11);
  std::string why;
  const std::optional<ExcessLossFit> naive = fit_excess_loss(samples, &why);
  ASSERT_TRUE(naive) << why;
  EXPECT_GT(naive->offset_db - kOffset, 0.6);
  const std::optional<CensoredExcessLossFit> fit = fit_censored_excess_loss(samples, &why);
  ASSERT_TRUE(fit) << why;
  EXPECT_NEAR(fit->offset_db, kOffset, 0.3);
  EXPECT_NEAR(fit->spread_db, kScatter, 0.3);
  EXPECT_NEAR(fit->snr50_db, kThreshold, 0.3);
  EXPECT_LT(fit->width_db, 0.5);
}

TEST(CensoredExcessLoss, RefusesWithoutLossesOrWithoutScatter) {
  std::vector<PacketSample> all_decoded;
  for (int i = 0; i < 40; ++i) {
    PacketSample s;
    s.predicted_snr_db = 20 + i % 5;
    s.decoded = true;
    s.measured_snr_db = s.predicted_snr_db - 6 + (i % 3 - 1);
    all_decoded.push_back(s);
  }
  std::string why;
  EXPECT_FALSE(fit_censored_excess_loss(all_decoded, &why));
  EXPECT_NE(why.find("0 packets lost"), std::string::npos) << why;

  std::vector<PacketSample> exact = all_decoded;  // the simulator: measured = predicted + offset exactly
  for (PacketSample& s : exact) s.measured_snr_db = s.predicted_snr_db - 6;
  for (int i = 0; i < 10; ++i) {
    PacketSample s;
    s.predicted_snr_db = 5;
    exact.push_back(s);
  }
  EXPECT_FALSE(fit_censored_excess_loss(exact, &why));
  EXPECT_NE(why.find("no scatter"), std::string::npos) << why;
}

TEST(CensoredExcessLoss, CalibrateUsesItLinkByLink) {
  std::vector<PacketSample> samples = scattered(3000, 1.0, 7, "acoustic");
  // The same sender heard on a second link, 10 dB better and without
  // scatter: a calibration of its own.
  for (int i = 0; i < 40; ++i) {
    PacketSample s;
    s.link = "tether";
    s.src = 2;
    s.predicted_snr_db = 30;
    s.decoded = true;
    s.measured_snr_db = 34;
    samples.push_back(s);
  }
  const std::vector<LinkCalibration> links = calibrate_links(samples);
  ASSERT_EQ(links.size(), 2u);
  EXPECT_EQ(links[0].link, "acoustic");
  EXPECT_EQ(links[1].link, "tether");
  ASSERT_TRUE(links[0].censored);
  EXPECT_NEAR(links[0].offset_db(), kOffset, 0.3);
  EXPECT_FALSE(links[1].censored);
  EXPECT_NEAR(links[1].offset_db(), 4, 1e-12);
  const std::string block = physics_block(links[0]);
  EXPECT_NE(block.find("censored fit"), std::string::npos) << block;
  char expected[64];
  std::snprintf(expected, sizeof expected, "excess_loss_db: %.2f\n", -links[0].censored->offset_db);
  EXPECT_NE(block.find(expected), std::string::npos) << block;
  EXPECT_NE(calibration_report(links).find("link from modem 2 on link \"tether\": 40 packets"), std::string::npos)
      << calibration_report(links);
}

}  // namespace
}  // namespace acomms::eval
