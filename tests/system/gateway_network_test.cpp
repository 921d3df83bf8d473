// Gateways on the simulated clock (the network: gateway_network.h).
//
// Shown: a command from the shore reaches the vehicle once, through the
// buoy, which has not loaded the command's type and forwards its bytes
// intact; two nodes routing a destination to each other drop the message
// at its hop limit; a buoy whose custody is full leaves the message with
// the shore (no ACK) until it has room; a buoy restarted while it holds a
// message delivers it after the restart.

#include "gateway_network.h"

namespace acomms::gateway_test {
namespace {

using namespace std::chrono_literals;

TEST_F(GatewayNetwork, ACommandReachesAVehicleTheShoreCannotHearOnceThroughTheBuoy) {
  build_three();
  shore_->start();
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(60s);  // the buoy hears the vehicle: a learned route
  shore_->submit("net.Command", "src: 1 dest: 3 code: 417");
  const std::string sent = shore_->queues->find_queue("net.Command")->messages().front().encoded;
  scheduler_.run_for(300s);

  ASSERT_EQ(commands_received(*vehicle_), 1u);
  const auto& got = vehicle_->received.front();
  EXPECT_EQ(got.src, 1);
  // The buoy never loaded net.Command: it forwarded the shore's bytes as
  // they were.
  EXPECT_EQ(got.encoded, sent);
  EXPECT_EQ(buoy_->codec.find_type("net.Command"), nullptr);
  EXPECT_EQ(commands_received(*buoy_), 0u);
  // Custody passed: the shore's copy was acknowledged by the buoy, the
  // buoy's by the vehicle; nothing is held anywhere.
  EXPECT_EQ(shore_->queues->find_queue("net.Command")->size(), 0u);
  EXPECT_EQ(shore_journal_.stored(), 0u);
  // The buoy took two into custody: the command, and the vehicle's
  // end-to-end ack of it on its way back (route/receipt.h).
  EXPECT_EQ(buoy_->forwarder->stats().custody_taken, 2u);
  EXPECT_EQ(buoy_->custody_held(), 0u);
  EXPECT_EQ(buoy_journal_.stored(), 0u);
  EXPECT_EQ(vehicle_->forwarder->stats().delivered, 1u);
  // The vehicle learned the way back: the shore through the buoy.
  auto back = vehicle_->forwarder->routes().next_hop(1, scheduler_.clock().now_seconds());
  ASSERT_TRUE(back);
  EXPECT_EQ(back->node, 2);
}

TEST_F(GatewayNetwork, ANeighbourGetsPlainDcclAndAMessageWithNoRouteWaits) {
  build_three();
  shore_->start();
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(60s);
  vehicle_->submit("net.Status", "src: 3 dest: 2 battery: 80");
  const std::string sent = vehicle_->queues->find_queue("net.Status")->messages().front().encoded;
  shore_->submit("net.Command", "src: 1 dest: 5 code: 1");  // node 5: no route
  scheduler_.run_for(300s);
  // The buoy is the vehicle's neighbour: the status went as plain DCCL,
  // no envelope.
  ASSERT_EQ(buoy_->received.size(), 1u);
  EXPECT_EQ(buoy_->received.front().encoded, sent);
  EXPECT_EQ(buoy_->forwarder->stats().delivered, 0u);
  // Node 5 has no route: the command waits on the shore, unsent.
  const queue::Queue& commands = *shore_->queues->find_queue("net.Command");
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_EQ(shore_->queues->stats("net.Command").sent, 0u);
  EXPECT_EQ(shore_->forwarder->waiting(commands, commands.messages().front()), "no route to node 5");
}

TEST_F(GatewayNetwork, AMessageArrivingTwiceByTwoPathsIsDeliveredOnce) {
  build_three();
  shore_->start();
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 5");
  scheduler_.run_for(300s);
  ASSERT_EQ(commands_received(*vehicle_), 1u);
  // A second copy of the same message (same identity, same bytes) comes
  // by another path: the buoy hands the vehicle exactly what it sent.
  route::Envelope copy;
  copy.origin = 1;
  copy.destination = 3;
  copy.seq = static_cast<uint16_t>(shore_journal_.events().front().message_id & 0xffff);
  copy.hops = 2;
  copy.ttl_s = 1000;
  copy.payload = vehicle_->received.front().encoded;
  const std::string frame = route::encode_envelope(copy, route::kDefaultEnvelopeId);
  EXPECT_TRUE(vehicle_->queues->receive(frame, 2, std::nullopt, 0, 3).empty());
  EXPECT_EQ(vehicle_->forwarder->stats().duplicates, 1u);
  EXPECT_EQ(commands_received(*vehicle_), 1u);
}

TEST_F(GatewayNetwork, TwoNodesRoutingToEachOtherDropTheMessageAtItsHopLimit) {
  // Node 9 is nowhere: the shore sends it to the buoy, the buoy back.
  build_shore(R"(hop_limit: 4 route { dest: 3 next_hop: 2 link: "sat" } route { dest: 9 next_hop: 2 link: "sat" })");
  build_buoy(R"(route { dest: 9 next_hop: 1 link: "sat" })");
  shore_->start();
  buoy_->start();
  shore_->submit("net.Command", "src: 1 dest: 9 code: 1");
  scheduler_.run_for(600s);
  // Hops 1 (shore to buoy), 2 (back), 3 (to buoy), 4 (back): the shore
  // holds it at hops 4 of 4 and drops it.
  EXPECT_EQ(buoy_->forwarder->stats().custody_taken, 2u);
  EXPECT_EQ(shore_->forwarder->stats().custody_taken, 1u);
  EXPECT_EQ(shore_->forwarder->stats().hop_limit_dropped + buoy_->forwarder->stats().hop_limit_dropped, 1u);
  EXPECT_EQ(shore_->custody_held() + buoy_->custody_held(), 0u);
  EXPECT_EQ(shore_journal_.stored() + buoy_journal_.stored(), 0u);
}

TEST_F(GatewayNetwork, AFullBuoyRefusesCustodyAndTheShoreKeepsTheMessage) {
  build_three("max_custody: 1");
  shore_->start();
  buoy_->start();
  // The vehicle is off: the buoy has no route and holds what it takes.
  shore_->submit("net.Command", "src: 1 dest: 3 code: 1");
  scheduler_.run_for(120s);
  ASSERT_EQ(buoy_->custody_held(), 1u);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 2");
  scheduler_.run_for(300s);
  EXPECT_EQ(buoy_->custody_held(), 1u);
  EXPECT_GT(buoy_->forwarder->stats().custody_refused, 0u);
  // No ACK for the refused one: the shore still holds it.
  EXPECT_EQ(shore_->queues->find_queue("net.Command")->size(), 1u);
  vehicle_->start();
  scheduler_.run_for(600s);
  EXPECT_EQ(commands_received(*vehicle_), 2u);
  EXPECT_EQ(shore_->queues->find_queue("net.Command")->size(), 0u);
  EXPECT_EQ(buoy_->custody_held(), 0u);
}

// The buoy's satellite link is down (disabled): it goes on taking the
// vehicle's statuses for the shore into custody up to its bound, lists
// what it holds (origin, destination), refuses the rest (the vehicle keeps
// them), and delivers everything once the link is back.
TEST_F(GatewayNetwork, ABuoyWhoseSatelliteIsDownTakesAcousticTrafficWithinItsBoundAndSaysWhatItHolds) {
  build_shore("");
  build_buoy(R"(max_custody: 3 route { dest: 1 next_hop: 1 link: "sat" })");
  vehicle_ = std::make_unique<GatewayNode>(3, std::vector{status_proto(), command_proto()}, kCommandQueues,
                                           R"(route { dest: 1 next_hop: 2 link: "acoustic" })",
                                           std::vector<LinkSpec>{{"acoustic", acoustic_, kAcousticCycle}}, scheduler_,
                                           vehicle_journal_);
  buoy_->choice->set_enabled(0, false);  // "sat"
  shore_->start();
  buoy_->start();
  vehicle_->start();
  for (int battery = 1; battery <= 5; ++battery) {
    vehicle_->submit("net.Status", "src: 3 dest: 1 battery: " + std::to_string(battery));
  }
  scheduler_.run_for(900s);
  EXPECT_EQ(buoy_->custody_held(), 3u);
  EXPECT_GT(buoy_->forwarder->stats().custody_refused, 0u);
  EXPECT_EQ(vehicle_->queues->find_queue("net.Status")->size(), 2u);  // refused: the vehicle keeps them
  size_t listed = 0;
  for (const queue::Queue* q : buoy_->queues->queues()) {
    for (const queue::QueuedMessage& m : q->messages()) {
      const std::string held = buoy_->forwarder->custody_json(*q, m);
      EXPECT_NE(held.find("\"origin\":3,\"destination\":1,"), std::string::npos) << held;
      listed += !held.empty();
    }
  }
  EXPECT_EQ(listed, 3u);
  size_t statuses = 0;
  for (const auto& r : shore_->received) statuses += r.type == "net.Status";
  EXPECT_EQ(statuses, 0u);

  buoy_->choice->set_enabled(0, true);
  scheduler_.run_for(1800s);
  statuses = 0;
  for (const auto& r : shore_->received) statuses += r.type == "net.Status";
  EXPECT_EQ(statuses, 5u);
  EXPECT_EQ(buoy_->custody_held(), 0u);
  EXPECT_EQ(vehicle_->queues->find_queue("net.Status")->size(), 0u);
}

TEST_F(GatewayNetwork, ABuoyThatCannotStoreTheMessageDoesNotAcknowledgeIt) {
  FailingJournal failing;
  failing.fail_appends = true;
  build_shore(R"(route { dest: 3 next_hop: 2 link: "sat" })");
  build_buoy_on("", failing);
  build_vehicle();
  shore_->start();
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 9");
  scheduler_.run_for(300s);
  // Tried, not stored, not acknowledged: the shore keeps it.
  EXPECT_GT(buoy_->forwarder->stats().custody_taken, 0u);
  EXPECT_EQ(buoy_->custody_held(), 0u);
  EXPECT_EQ(commands_received(*vehicle_), 0u);
  EXPECT_EQ(shore_->queues->find_queue("net.Command")->size(), 1u);
  // The disk has room again: the next resend goes through, once.
  failing.fail_appends = false;
  scheduler_.run_for(300s);
  EXPECT_EQ(commands_received(*vehicle_), 1u);
  EXPECT_EQ(shore_->queues->find_queue("net.Command")->size(), 0u);
}

TEST_F(GatewayNetwork, ABuoyRestartedWhileHoldingAMessageDeliversItAfterwards) {
  build_three();
  shore_->start();
  buoy_->start();
  shore_->submit("net.Command", "src: 1 dest: 3 code: 77");
  shore_->submit("net.Command", "src: 1 dest: 3 code: 78");
  scheduler_.run_for(120s);
  ASSERT_EQ(buoy_->custody_held(), 2u);
  ASSERT_EQ(shore_->queues->find_queue("net.Command")->size(), 0u);  // custody passed
  // The buoy stops and comes back from its journal.
  buoy_.reset();
  build_buoy("");
  EXPECT_EQ(buoy_->custody_held(), 2u);
  // What `queue ls` shows of them: the envelope's head, one hop taken.
  const queue::Queue* custody = buoy_->queues->find_queue("acomms.route.Custody.v10");
  ASSERT_NE(custody, nullptr);
  const std::string json = buoy_->forwarder->custody_json(*custody, custody->messages().front());
  EXPECT_NE(json.find(R"("origin":1,"destination":3,)"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("hops":2,"hop_limit":8)"), std::string::npos) << json;
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(300s);
  EXPECT_EQ(commands_received(*vehicle_), 2u);
  EXPECT_EQ(buoy_->custody_held(), 0u);
  EXPECT_EQ(buoy_journal_.stored(), 0u);
}

}  // namespace
}  // namespace acomms::gateway_test
