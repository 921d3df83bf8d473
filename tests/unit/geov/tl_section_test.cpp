// The map's environment section planned from what the daemon holds: the
// newest profile instance's sound speed, a bounded receiver grid reaching a
// quarter past the vehicle, rays allowed that far; refused (with the
// status the page shows) without sound speed or beyond the longest section.
#include <gtest/gtest.h>

#include "geov/tl_section.h"

namespace acomms::cli::geov {
namespace {

gram::KnownEnvironment held(double bottom_m = 100) {
  gram::KnownEnvironment k;
  gram::Environment& base = *k.mutable_base();
  base.set_frequency_hz(10000);
  base.set_source_depth_m(5);
  for (double z : {0.0, bottom_m}) {
    auto* p = base.add_sound_speed();
    p->set_depth_m(z);
    p->set_speed_mps(1500 - z / 10);
  }
  return k;
}

TEST(TlSectionPlan, TheGridReachesAQuarterPastTheVehicleWithinBounds) {
  const SectionPlan plan = plan_section(held(), 1000);
  EXPECT_EQ(plan.range_m, 1000);
  EXPECT_EQ(plan.length_m, 1250);
  ASSERT_EQ(plan.request.receiver_range_m_size(), kRanges);
  ASSERT_EQ(plan.request.receiver_depth_m_size(), kDepths);
  EXPECT_EQ(plan.request.receiver_range_m(kRanges - 1), 1250);
  EXPECT_EQ(plan.request.receiver_depth_m(0), 0);
  EXPECT_EQ(plan.request.receiver_depth_m(kDepths - 1), 100);
  EXPECT_GE(plan.request.box_range_m(), 1250);
  // The request leaves the held environment's physics to the daemon.
  EXPECT_EQ(plan.request.sound_speed_size(), 0);
  EXPECT_EQ(plan.request.frequency_hz(), 0);
  // The picture's environment is the held one with the section's grid.
  EXPECT_EQ(plan.drawn.source_depth_m(), 5);
  EXPECT_EQ(plan.drawn.receiver_range_m_size(), kRanges);
  // A vehicle close by still gets a readable section.
  EXPECT_EQ(plan_section(held(), 3).length_m, kMinSectionM);
}

TEST(TlSectionPlan, TheNewestProfileInstanceIsDrawnAndAShallowerBottomBoundsTheDepths) {
  gram::KnownEnvironment k = held(200);
  for (double c : {1490.0, 1480.0}) {
    auto* instance = k.add_instances();
    for (double z : {0.0, 200.0}) {
      auto* p = instance->add_sound_speed();
      p->set_depth_m(z);
      p->set_speed_mps(c);
    }
  }
  auto* b = k.mutable_base()->add_bathymetry();
  b->set_range_m(0);
  b->set_depth_m(150);
  const SectionPlan plan = plan_section(k, 500);
  EXPECT_EQ(plan.drawn.sound_speed(0).speed_mps(), 1480);
  EXPECT_EQ(plan.request.receiver_depth_m(kDepths - 1), 150);
}

TEST(TlSectionPlan, NoSoundSpeedOrAVehicleTooFarIsRefusedWithItsStatus) {
  gram::KnownEnvironment none;
  none.mutable_base()->set_frequency_hz(10000);
  try {
    plan_section(none, 100);
    FAIL() << "planned without sound speed";
  } catch (const SectionRefusal& r) {
    EXPECT_EQ(r.status, 503);
    EXPECT_NE(r.text.find("the daemon holds no environment"), std::string::npos) << r.text;
    EXPECT_NE(r.text.find("gram env update --ctd"), std::string::npos) << r.text;
  }
  try {
    plan_section(held(), kMaxSectionM);
    FAIL() << "planned beyond the longest section";
  } catch (const SectionRefusal& r) {
    EXPECT_EQ(r.status, 422);
    EXPECT_NE(r.text.find("the vehicle is 50000 m from the buoy; the map draws sections up to 40000 m"),
              std::string::npos)
        << r.text;
  }
  EXPECT_NO_THROW(plan_section(held(), kMaxSectionM / 1.25));
}

}  // namespace
}  // namespace acomms::cli::geov
