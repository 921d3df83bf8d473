// The route table (route/route_table.h): static routes in config order,
// routes learned from traffic with their age, and config errors that name
// the field.
#include "route/route_table.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace acomms::route {
namespace {

v1::RoutingConfig parse(const std::string& text) {
  v1::RoutingConfig config;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &config)) << text;
  return config;
}

const std::vector<std::string> kLinks{"acoustic", "sat"};

TEST(RouteTableTest, StaticRoutesMatchInConfigOrderExactBeforeRange) {
  RouteTable table(parse(R"(route { dest: 12 next_hop: 3 link: "acoustic" }
                            route { dest_min: 10 dest_max: 19 next_hop: 2 link: "sat" })"),
                   kLinks, 1);
  EXPECT_EQ(table.next_hop(12, 0), (NextHop{3, "acoustic", RouteSource::kStatic}));
  EXPECT_EQ(table.next_hop(10, 0), (NextHop{2, "sat", RouteSource::kStatic}));
  EXPECT_EQ(table.next_hop(19, 0), (NextHop{2, "sat", RouteSource::kStatic}));
  EXPECT_FALSE(table.next_hop(20, 0));
  EXPECT_FALSE(table.next_hop(9, 0));
}

TEST(RouteTableTest, ARouteWithoutALinkTakesTheFirst) {
  RouteTable table(parse("route { dest: 5 next_hop: 2 }"), kLinks, 1);
  EXPECT_EQ(table.next_hop(5, 0)->link, "acoustic");
}

TEST(RouteTableTest, ThisNodeIsNeverRoutedEvenInsideARange) {
  RouteTable table(parse("route { dest_min: 1 dest_max: 100 next_hop: 2 }"), kLinks, 7);
  EXPECT_FALSE(table.next_hop(7, 0));
  EXPECT_TRUE(table.next_hop(8, 0));
}

TEST(RouteTableTest, AHeardNodeIsReachableDirectlyUntilItsRouteAges) {
  v1::RoutingConfig config = parse("learned_max_age_s: 100");
  RouteTable table(config, kLinks, 2);
  EXPECT_FALSE(table.next_hop(3, 0));
  table.heard(3, "acoustic", 50);
  EXPECT_EQ(table.next_hop(3, 60), (NextHop{3, "acoustic", RouteSource::kLearnedDirect}));
  EXPECT_TRUE(table.next_hop(3, 150));
  EXPECT_FALSE(table.next_hop(3, 151));  // 101 s since last heard
  auto rows = table.list(151);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows[0].stale);
  EXPECT_EQ(rows[0].last_confirmed, 50);
  table.heard(3, "acoustic", 200);  // heard again: fresh again
  EXPECT_TRUE(table.next_hop(3, 201));
  EXPECT_FALSE(table.list(201)[0].stale);
}

TEST(RouteTableTest, ARelayedOriginIsReachableThroughItsRelayButADirectNeighbourWins) {
  RouteTable table(parse("learned_max_age_s: 100"), kLinks, 1);
  table.heard_through(12, 2, "sat", 10);
  EXPECT_EQ(table.next_hop(12, 20), (NextHop{2, "sat", RouteSource::kLearnedRelay}));
  // Heard itself, again and again (RouteTable::kDirectHearings): direct.
  table.heard(12, "acoustic", 28);
  table.heard(12, "acoustic", 29);
  table.heard(12, "acoustic", 30);
  EXPECT_EQ(table.next_hop(12, 40), (NextHop{12, "acoustic", RouteSource::kLearnedDirect}));
  table.heard_through(12, 2, "sat", 50);  // the relay again, the direct hearing fresh: kept
  EXPECT_EQ(table.next_hop(12, 60)->source, RouteSource::kLearnedDirect);
  table.heard_through(12, 2, "sat", 200);  // the direct hearing aged: the relay takes over
  EXPECT_EQ(table.next_hop(12, 210), (NextHop{2, "sat", RouteSource::kLearnedRelay}));
}

TEST(RouteTableTest, OnePacketOverheardFromARelayedNodeDoesNotTurnItsRouteDirect) {
  RouteTable table(parse("learned_max_age_s: 100"), kLinks, 1);
  table.heard_through(12, 2, "sat", 10);
  table.heard(12, "acoustic", 20);  // once, at the fringe of range
  table.heard(12, "acoustic", 21);
  EXPECT_EQ(table.next_hop(12, 22), (NextHop{2, "sat", RouteSource::kLearnedRelay}));
  table.heard_through(12, 2, "sat", 30);  // the relay confirmed: the count starts again
  table.heard(12, "acoustic", 31);
  table.heard(12, "acoustic", 32);
  EXPECT_EQ(table.next_hop(12, 33)->source, RouteSource::kLearnedRelay);
  // An ACK from it to this node: both ways work, direct at once.
  table.heard(12, "acoustic", 34, /*two_way=*/true);
  EXPECT_EQ(table.next_hop(12, 35), (NextHop{12, "acoustic", RouteSource::kLearnedDirect}));
}

TEST(RouteTableTest, StaticRoutesWinOverLearnedAndAreConfirmedByTheirNextHop) {
  RouteTable table(parse(R"(route { dest: 12 next_hop: 2 link: "sat" })"), kLinks, 1);
  table.heard(12, "acoustic", 5);
  EXPECT_EQ(table.next_hop(12, 6)->source, RouteSource::kStatic);
  EXPECT_FALSE(table.list(6)[0].last_confirmed);
  table.heard(2, "acoustic", 7);  // the next hop, but on another link
  EXPECT_FALSE(table.list(8)[0].last_confirmed);
  table.heard(2, "sat", 9);
  EXPECT_EQ(table.list(10)[0].last_confirmed, 9);
  EXPECT_EQ(std::string(to_string(table.list(10)[0].next.source)), "static");
}

void expect_refused(const std::string& text, const std::string& names) {
  try {
    RouteTable table(parse(text), kLinks, 1);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(names), std::string::npos) << e.what();
  }
}

TEST(RouteTableTest, BadRoutesAreRefusedNamingTheField) {
  expect_refused("route { next_hop: 2 }", "routing.route[0]: give either dest");
  expect_refused("route { dest: 3 dest_min: 1 dest_max: 4 next_hop: 2 }", "routing.route[0]: give either");
  expect_refused("route { dest_min: 3 next_hop: 2 }", "needs both dest_min and dest_max");
  expect_refused("route { dest_min: 5 dest_max: 4 next_hop: 2 }", "dest_min 5 is above dest_max 4");
  expect_refused("route { dest: 0 next_hop: 2 }", "routing.route[0].dest: node ids are 1..65535");
  expect_refused("route { dest: 70000 next_hop: 2 }", "node ids are 1..65535");
  expect_refused("route { dest: 3 next_hop: 2 } route { dest: 4 next_hop: 1 }", "routing.route[1].next_hop 1");
  expect_refused(R"(route { dest: 3 next_hop: 2 link: "radio" })", "routing.route[0].link \"radio\"");
  expect_refused("learned_max_age_s: 0", "routing.learned_max_age_s");
}

}  // namespace
}  // namespace acomms::route
