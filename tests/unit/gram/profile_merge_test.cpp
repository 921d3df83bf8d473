// Merging a cast into a base profile and thinning (spec §2.6).
#include <gtest/gtest.h>

#include "gram/profile_merge.h"

namespace acomms::gram {
namespace {

Profile profile(std::initializer_list<std::pair<double, double>> points) {
  Profile out;
  for (const auto& [z, c] : points) {
    SoundSpeedPoint p;
    p.set_depth_m(z);
    p.set_speed_mps(c);
    out.push_back(p);
  }
  return out;
}

std::vector<std::pair<double, double>> pairs(const Profile& p) {
  std::vector<std::pair<double, double>> out;
  for (const auto& point : p) out.emplace_back(point.depth_m(), point.speed_mps());
  return out;
}

const Profile kBase = profile({{0, 1500}, {50, 1495}, {100, 1490}, {200, 1492}});
const Profile kCast = profile({{20, 1510}, {40, 1505}, {80, 1498}});

TEST(GramProfileMerge, MergeReplacesTheBaseInsideTheCastsSpanAndKeepsItOutside) {
  EXPECT_EQ(pairs(merge_cast(kBase, kCast, CastMerge::kMerge)),
            (std::vector<std::pair<double, double>>{{0, 1500}, {20, 1510}, {40, 1505}, {80, 1498}, {100, 1490}, {200, 1492}}));
}

TEST(GramProfileMerge, OverwriteExtendsTheCastToTheSurfaceAndTheBottom) {
  EXPECT_EQ(pairs(merge_cast(kBase, kCast, CastMerge::kOverwrite)),
            (std::vector<std::pair<double, double>>{{0, 1510}, {20, 1510}, {40, 1505}, {80, 1498}, {200, 1498}}));
  EXPECT_EQ(pairs(merge_cast(kBase, kCast, CastMerge::kOverwriteWithBaseBelow)),
            (std::vector<std::pair<double, double>>{{0, 1510}, {20, 1510}, {40, 1505}, {80, 1498}, {100, 1490}, {200, 1492}}));
}

TEST(GramProfileMerge, ACastDeeperThanTheBottomEndsAtTheBottom) {
  const Profile deep = profile({{150, 1491}, {250, 1493}});
  EXPECT_EQ(pairs(merge_cast(kBase, deep, CastMerge::kMerge)),
            (std::vector<std::pair<double, double>>{{0, 1500}, {50, 1495}, {100, 1490}, {150, 1491}, {200, 1492}}));
}

TEST(GramProfileMerge, ThinningDropsPointsALineExplainsAndKeepsTheKinks) {
  const Profile fine = profile({{0, 1500}, {1, 1500.01}, {2, 1500.02}, {3, 1500.03}, {4, 1499}, {5, 1498.02}, {6, 1497}});
  EXPECT_EQ(pairs(thin_profile(fine, 0.05)),
            (std::vector<std::pair<double, double>>{{0, 1500}, {3, 1500.03}, {6, 1497}}));
  // A tolerance above every deviation leaves the two ends.
  EXPECT_EQ(pairs(thin_profile(fine, 2.0)), (std::vector<std::pair<double, double>>{{0, 1500}, {6, 1497}}));
}

}  // namespace
}  // namespace acomms::gram
