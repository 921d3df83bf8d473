// The environment the vehicle knows: field-by-field merge, CTD casts kept
// as instances within the window, runs resolved from them.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "gram/bellhop_import.h"
#include "gram/environment_merge.h"
#include "gram/vehicle_environment.h"

namespace acomms::gram {
namespace {

Environment base() {
  return import_bellhop_env_file(std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/pekeris_lossy_500hz.env")
      .environment;
}

std::string cast_csv(double warm) {
  std::ostringstream csv;
  csv << "lat_deg,depth_m,t90_degc,s_psu\n";
  for (int z = 0; z <= 60; z += 2) csv << "45," << z << "," << warm - z * 0.1 << ",35\n";
  return csv.str();
}

TEST(GramEnvironmentMerge, SetFieldsReplaceSubMessagesMergeAndListsAreReplacedWhole) {
  Environment held = base();
  held.mutable_bottom()->set_kind(Boundary::HALF_SPACE);
  held.mutable_bottom()->mutable_half_space()->set_speed_mps(1600);
  held.mutable_bottom()->mutable_half_space()->set_density_ratio(1.8);
  Environment change;
  change.set_source_depth_m(33);
  change.mutable_bottom()->mutable_half_space()->set_speed_mps(1700);
  change.add_receiver_range_m(5);
  const Environment merged = merge_environment(held, change);
  EXPECT_EQ(merged.source_depth_m(), 33);
  EXPECT_EQ(merged.bottom().kind(), Boundary::HALF_SPACE);
  EXPECT_EQ(merged.bottom().half_space().speed_mps(), 1700);
  EXPECT_EQ(merged.bottom().half_space().density_ratio(), 1.8);
  ASSERT_EQ(merged.receiver_range_m_size(), 1);
  EXPECT_EQ(merged.sound_speed_size(), held.sound_speed_size());
  EXPECT_EQ(merged.frequency_hz(), held.frequency_hz());
}

TEST(GramEnvironmentMerge, TheMaskSetsZerosAndFirstEnumValues) {
  Environment held = base();
  held.mutable_bottom()->set_kind(Boundary::RIGID);
  held.set_source_depth_m(50);
  const Environment merged = merge_environment(held, Environment(), {"bottom.kind", "source_depth_m"});
  EXPECT_EQ(merged.bottom().kind(), Boundary::VACUUM);
  EXPECT_EQ(merged.source_depth_m(), 0);
}

TEST(GramEnvironmentMerge, AMaskPathThatIsNoFieldIsNamed) {
  try {
    merge_environment(base(), Environment(), {"bottom.knd"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"bottom.knd\""), std::string::npos) << e.what();
  }
}

TEST(GramVehicleEnvironment, CastsBecomeInstancesAndOldOnesLeaveTheWindow) {
  VehicleEnvironment known(base(), {1.0, 0.0, 1800.0});
  int persisted = 0;
  auto count = [&](const KnownEnvironment&) { ++persisted; };
  EnvironmentChange first;
  first.casts.push_back({1000.0, cast_csv(20), "a.csv"});
  known.update(first, count);
  EnvironmentChange later;
  later.casts.push_back({2000.0, cast_csv(15), "b.csv"});
  later.casts.push_back({3000.0, cast_csv(10), "c.csv"});
  const KnownEnvironment state = known.update(later, count);
  EXPECT_EQ(persisted, 2);
  ASSERT_EQ(state.instances_size(), 2);  // 1000 s is more than 1800 s before 3000 s
  EXPECT_EQ(state.instances(0).time_s(), 2000.0);
  EXPECT_EQ(state.instances(1).samples(), 31u);
  // Merged into the base profile: the cast's span is measured, below it the base.
  const auto& ssp = state.instances(1).sound_speed();
  EXPECT_EQ(ssp[ssp.size() - 1].depth_m(), base().sound_speed(base().sound_speed_size() - 1).depth_m());

  const auto one = known.resolve(Environment(), {}, false);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].sound_speed(0).speed_mps(), state.instances(1).sound_speed(0).speed_mps());
  EXPECT_EQ(known.resolve(Environment(), {}, true).size(), 2u);
  Environment own;
  *own.mutable_sound_speed() = base().sound_speed();
  EXPECT_EQ(known.resolve(own, {}, true).size(), 1u);
}

TEST(GramVehicleEnvironment, ABadCastChangesNothingAndNamesTheLine) {
  VehicleEnvironment known(base(), {});
  EnvironmentChange change;
  change.base.set_source_depth_m(44);
  change.casts.push_back({1.0, "lat_deg,depth_m,t90_degc,s_psu\n45,0,10,35\n45,x,10,35\n", "bad.csv"});
  bool persisted = false;
  try {
    known.update(change, [&](const KnownEnvironment&) { persisted = true; });
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(persisted);
  EXPECT_EQ(known.snapshot().base().source_depth_m(), base().source_depth_m());
}

}  // namespace
}  // namespace acomms::gram
