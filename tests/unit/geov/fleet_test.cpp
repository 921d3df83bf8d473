// The map's model of the fleet: one copy of each (vehicle, time), heading
// from the last two positions, and the numbered updates a page resumes from.
#include <gtest/gtest.h>

#include "geov/fleet.h"

namespace acomms::cli::geov {
namespace {

using namespace std::chrono_literals;

telemetry::Position at(int32_t src, double t, double x, double y) {
  telemetry::Position p;
  p.set_src(src);
  p.set_time(t);
  p.set_x(x);
  p.set_y(y);
  p.set_depth(10);
  p.set_z(-10);
  return p;
}

TEST(Fleet, StoresEachVehicleTimeOnceWhateverTheSource) {
  Fleet fleet;
  EXPECT_EQ(fleet.add_positions({at(1, 100, 0, 0), at(1, 101, 1, 0)}), 2);
  EXPECT_EQ(fleet.add_positions({at(1, 101, 1, 0), at(1, 102, 2, 0), at(3, 101, 5, 5)}), 2);
  EXPECT_EQ(fleet.history(0, 1e12).at(1).size(), 3u);
  EXPECT_EQ(fleet.last_time(1), 102);
  EXPECT_EQ(fleet.last_time(2), 0);
  EXPECT_EQ(fleet.vehicles(), (std::set<int32_t>{1, 3}));
  EXPECT_EQ(fleet.history(101, 101).at(1).size(), 1u);
  EXPECT_EQ(fleet.history(0, 1e12, 3).size(), 1u);
}

TEST(Fleet, HeadingIsFromTheLastTwoPositionsClockwiseFromNorth) {
  Fleet fleet;
  fleet.add_positions({at(1, 100, 0, 0), at(1, 101, 10, 0)});  // east
  EXPECT_NE(fleet.snapshot_json(0).find("\"heading\":90,"), std::string::npos) << fleet.snapshot_json(0);
  fleet.add_positions({at(1, 102, 10, -10)});  // south
  EXPECT_NE(fleet.snapshot_json(0).find("\"heading\":180,"), std::string::npos);
}

TEST(Fleet, UpdatesAfterAnIdAreEveryLaterOneAndAStaleIdResets) {
  Fleet fleet(1000, 3);
  fleet.add_positions({at(1, 100, 0, 0)});
  fleet.add_positions({at(1, 101, 0, 0)});
  fleet.add_positions({at(2, 101, 0, 0)});
  FleetUpdates after1 = fleet.updates_after(fleet.epoch(), 1, 0ms);
  EXPECT_FALSE(after1.reset);
  ASSERT_EQ(after1.events.size(), 2u);
  EXPECT_EQ(after1.events[0].first, 2u);
  EXPECT_NE(after1.events[1].second.find("\"src\":2"), std::string::npos);
  fleet.add_positions({at(2, 102, 0, 0)});  // the ring holds 3: update 1 is gone
  EXPECT_TRUE(fleet.updates_after(fleet.epoch(), 0, 0ms).reset);
  EXPECT_FALSE(fleet.updates_after(fleet.epoch(), 1, 0ms).reset);
  EXPECT_TRUE(fleet.updates_after(fleet.epoch() + 1, 4, 0ms).reset);  // another server's ids
  EXPECT_TRUE(fleet.updates_after(fleet.epoch(), 99, 0ms).reset);     // ahead of this server
  EXPECT_TRUE(fleet.updates_after(fleet.epoch(), 4, 0ms).events.empty());
}

TEST(Fleet, AVehicleHeardShowsItsLinkFiguresAndWhen) {
  Fleet fleet;
  fleet.add_positions({at(2, 100, 0, 0)});
  EXPECT_NE(fleet.snapshot_json(0).find("\"last_heard\":0,\"link\":null"), std::string::npos) << fleet.snapshot_json(0);
  v1::LinkFigures figures;
  figures.set_rate(3);
  figures.set_snr_in_db(12.5);
  const uint64_t before = fleet.last_update_id();
  fleet.heard(2, 105, &figures);
  EXPECT_EQ(fleet.last_update_id(), before + 1);  // pushed to the pages
  std::string json = fleet.snapshot_json(0);
  EXPECT_NE(json.find("\"last_heard\":105,\"link\":{\"rate\":3,\"snr_in_db\":12.5,\"snr_out_db\":null"),
            std::string::npos) << json;
  fleet.heard(2, 104, nullptr);  // older, no figures: nothing to show
  EXPECT_EQ(fleet.last_update_id(), before + 1);
  fleet.heard(2, 110, nullptr);  // heard again, without figures: the last ones stay
  json = fleet.snapshot_json(0);
  EXPECT_NE(json.find("\"last_heard\":110,\"link\":{\"rate\":3,\"snr_in_db\":12.5"), std::string::npos) << json;
}

TEST(Fleet, QueuedMessagesAreListedForTheirDestination) {
  Fleet fleet;
  fleet.add_positions({at(2, 100, 0, 0)});
  const uint64_t before = fleet.last_update_id();
  fleet.set_queued("a", {{2, {{7, "gv.Command", 99, true}}}});
  EXPECT_EQ(fleet.last_update_id(), before + 1);
  fleet.set_queued("a", {{2, {{7, "gv.Command", 99, true}}}});  // no change, no update
  EXPECT_EQ(fleet.last_update_id(), before + 1);
  const std::string json = fleet.snapshot_json(0);
  EXPECT_NE(json.find("\"queued_count\":1,\"queued\":[{\"id\":7,\"type\":\"gv.Command\""), std::string::npos) << json;
}

TEST(Fleet, AWaitingStreamWakesOnAPositionAndOnClose) {
  Fleet fleet;
  std::thread adder([&] {
    std::this_thread::sleep_for(50ms);
    fleet.add_positions({at(1, 100, 0, 0)});
  });
  FleetUpdates got = fleet.updates_after(fleet.epoch(), 0, 10s);
  adder.join();
  ASSERT_EQ(got.events.size(), 1u);
  fleet.close();
  EXPECT_TRUE(fleet.updates_after(fleet.epoch(), 1, 10s).closed);
}

}  // namespace
}  // namespace acomms::cli::geov
