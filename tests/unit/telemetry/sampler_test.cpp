// The sampler: fixes at any rate in, a sample at every multiple of tau out.

#include <gtest/gtest.h>

#include <cmath>

#include "telemetry/sampler.h"

namespace acomms::telemetry {
namespace {

TEST(Sampler, InterpolatesBetweenFixesAtMultiplesOfTau) {
  const std::vector<Sample> samples =
      sample_track({{3, {0, 0, 0}}, {13, {10, -20, -1}}, {23, {20, -20, -6}}}, 10);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[0].time_s, 10);
  EXPECT_DOUBLE_EQ(samples[0].position_m[0], 7);
  EXPECT_DOUBLE_EQ(samples[0].position_m[1], -14);
  EXPECT_TRUE(samples[0].new_segment);
  EXPECT_EQ(samples[1].time_s, 20);
  EXPECT_DOUBLE_EQ(samples[1].position_m[0], 17);
  EXPECT_DOUBLE_EQ(samples[1].position_m[2], -4.5);
  EXPECT_FALSE(samples[1].new_segment);
}

TEST(Sampler, AFixOnTheGridIsASampleAndAFastRateGivesOneSamplePerTau) {
  std::vector<Fix> fixes;
  for (int t = 0; t <= 30; ++t) fixes.push_back({static_cast<double>(t), {1.0 * t, 0, 0}});
  const std::vector<Sample> samples = sample_track(fixes, 10);
  ASSERT_EQ(samples.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(samples[i].time_s, static_cast<int64_t>(10 * i));
    EXPECT_DOUBLE_EQ(samples[i].position_m[0], 10.0 * i);
    EXPECT_EQ(samples[i].new_segment, i == 0);
  }
}

TEST(Sampler, AGapLongerThanTauStartsANewSegment) {
  const std::vector<Sample> samples = sample_track(
      {{0, {0, 0, 0}}, {10, {1, 0, 0}}, {20, {2, 0, 0}}, {45, {50, 0, 0}}, {50, {55, 0, 0}}, {60, {60, 0, 0}}}, 10);
  ASSERT_EQ(samples.size(), 5u);
  EXPECT_EQ(samples[2].time_s, 20);
  EXPECT_FALSE(samples[2].new_segment);
  // nothing interpolated across the gap (20..45); the next is at 50
  EXPECT_EQ(samples[3].time_s, 50);
  EXPECT_TRUE(samples[3].new_segment);
  EXPECT_DOUBLE_EQ(samples[3].position_m[0], 55);
  EXPECT_FALSE(samples[4].new_segment);
}

TEST(Sampler, IgnoresFixesThatDoNotMoveTimeForwardAndRefusesNonFinite) {
  Sampler sampler(10);
  EXPECT_EQ(sampler.add({0, {0, 0, 0}}).size(), 1u);
  EXPECT_TRUE(sampler.add({0, {5, 0, 0}}).empty());
  EXPECT_TRUE(sampler.add({-3, {5, 0, 0}}).empty());
  EXPECT_THROW(sampler.add({5, {NAN, 0, 0}}), std::invalid_argument);
  const std::vector<Sample> next = sampler.add({10, {10, 0, 0}});
  ASSERT_EQ(next.size(), 1u);
  EXPECT_DOUBLE_EQ(next[0].position_m[0], 10);
}

}  // namespace
}  // namespace acomms::telemetry
