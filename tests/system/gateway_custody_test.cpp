// Gateways: what a gateway's queues must not do to the messages they hold
// (the network: gateway_network.h). Each test is a defect a review found:
//  - a message that must wait (no route, its next hop on another link) at
//    the head of its queue held back sendable ones behind it;
//  - a custody message stood at its custody queue's P (0 after every send)
//    against a link's cost, so it never beat the cost;
//  - a copy arriving while the first was being stored was ACKed whether
//    or not that store succeeded;
//  - on a link whose modem ACKs in hardware, refusing custody lost the
//    message (the previous hop had forgotten it at the modem's ACK); then
//    taking it over routing.max_custody broke the bound. Now the buoy
//    stores nothing and answers with a custody receipt ("refused").

#include "gateway_network.h"

namespace acomms::gateway_test {
namespace {

using namespace std::chrono_literals;

// A journal whose appends complete when the test says (a slow disk).
class DeferredJournal final : public JournalInMemory {
 public:
  using MessageJournal::append;
  void append(queue::JournalMessage message, Appended appended) override {
    held.push_back(std::move(appended));
  }
  void fail_all() {
    for (auto& appended : std::exchange(held, {})) appended(0, std::make_exception_ptr(std::runtime_error("disk")));
  }

  std::vector<Appended> held;
};

// An envelope from the shore (1) for the vehicle (3), as the buoy hears it.
std::string command_envelope(uint16_t seq) {
  route::Envelope e;
  e.origin = 1;
  e.destination = 3;
  e.seq = seq;
  e.ttl_s = 1000;
  e.payload = "opaque";
  return route::encode_envelope(e, route::kDefaultEnvelopeId);
}

TEST_F(GatewayNetwork, ACustodyMessageWithNoRouteDoesNotHoldBackOneBehindItForAnotherNode) {
  build_shore(R"(route { dest: 3 next_hop: 2 link: "sat" } route { dest: 9 next_hop: 2 link: "sat" })");
  build_buoy("");  // learns the vehicle; node 9 it never hears of
  build_vehicle();
  shore_->start();
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 9 code: 1");
  scheduler_.run_for(120s);
  ASSERT_EQ(buoy_->custody_held(), 1u);  // for node 9, first in its custody queue
  shore_->submit("net.Command", "src: 1 dest: 3 code: 2");
  scheduler_.run_for(300s);
  EXPECT_EQ(commands_received(*vehicle_), 1u);
  EXPECT_EQ(buoy_->custody_held(), 1u);  // node 9's still waits
  const queue::Queue* custody = buoy_->queues->find_queue("acomms.route.Custody.v10");
  ASSERT_NE(custody, nullptr);
  EXPECT_EQ(buoy_->forwarder->waiting(*custody, custody->messages().front()), "no route to node 9");
}

TEST_F(GatewayNetwork, AMessageWithNoRouteDoesNotHoldBackAnOlderOneOnItsOrigin) {
  build_three();
  shore_->start();
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 1");
  shore_->submit("net.Command", "src: 1 dest: 5 code: 2");  // newest first: the head, and no route
  scheduler_.run_for(300s);
  EXPECT_EQ(commands_received(*vehicle_), 1u);
  const queue::Queue& commands = *shore_->queues->find_queue("net.Command");
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_EQ(commands.messages().front().record.dest, 5);
}

TEST_F(GatewayNetwork, ACustodyMessageStandsAgainstALinkCostAtItsOwnValue) {
  build_shore(R"(route { dest: 3 next_hop: 2 link: "sat" })");
  // The buoy's acoustic link costs 0.5; net.Command is worth 1
  // (value_base), so it beats the cost on the buoy as on the shore.
  buoy_ = std::make_unique<GatewayNode>(
      2, std::vector{status_proto()}, kQueues, "",
      std::vector<LinkSpec>{{"sat", sat_, kSatCycle}, {"acoustic", acoustic_, kAcousticCycle, 0.5}}, scheduler_,
      buoy_journal_);
  build_vehicle();
  shore_->start();
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 7");
  scheduler_.run_for(300s);
  EXPECT_EQ(commands_received(*vehicle_), 1u);
  EXPECT_EQ(buoy_->custody_held(), 0u);
}

TEST_F(GatewayNetwork, ACopyArrivingWhileTheFirstIsStoredIsAcknowledgedOnlyIfTheStoreSucceeds) {
  DeferredJournal slow;
  build_buoy_on("", slow);
  // Two copies in one frame (a resend heard twice): the first is being
  // stored when the second comes.
  buoy_->queues->receive(command_envelope(5) + command_envelope(5), 1, std::nullopt, 0, 2);
  auto conditions = buoy_->queues->take_ack_conditions();
  ASSERT_EQ(conditions.size(), 2u);
  EXPECT_EQ(buoy_->forwarder->stats().custody_copies, 1u);
  slow.fail_all();
  // The store failed: neither copy may be acknowledged.
  EXPECT_FALSE(conditions[0]->load());
  EXPECT_FALSE(conditions[1]->load());
  EXPECT_EQ(buoy_->custody_held(), 0u);
}

TEST_F(GatewayNetwork, FullCustodyOnALinkWhoseModemAcksStoresNothingAndAnswersWithACustodyReceipt) {
  build_buoy("max_custody: 1");
  buoy_->queues->set_acks_in_hardware(0, true);  // "sat": an Iridium modem's
  buoy_->queues->receive(command_envelope(1), 1, std::nullopt, 0, 2);
  ASSERT_EQ(buoy_->custody_held(), 1u);
  buoy_->queues->take_ack_conditions();  // the modem ACKed already: they decide nothing there
  buoy_->queues->receive(command_envelope(2), 1, std::nullopt, 0, 2);
  EXPECT_EQ(buoy_->custody_held(), 1u) << "routing.max_custody is a hard bound on every link";
  EXPECT_EQ(buoy_->forwarder->stats().custody_refused, 1u);
  // What the buoy owes the shore on "sat": "taken" for 1/1, "refused" for 1/2.
  const double now = scheduler_.clock().now_seconds();
  EXPECT_EQ(buoy_->forwarder->owed_on(0, 1, 100, now),
            route::encode_custody_receipt({route::CustodyVerdict::kTaken, {1, 1}}, route::kDefaultEnvelopeId) +
                route::encode_custody_receipt({route::CustodyVerdict::kRefused, {1, 2}}, route::kDefaultEnvelopeId));
  EXPECT_EQ(buoy_->forwarder->owed_on(0, 1, 100, now), "") << "each receipt goes once";
  EXPECT_EQ(buoy_->forwarder->stats().custody_receipts_sent, 2u);
  // The same on a link with software ACKs: refused, the ACK withheld, no receipt.
  buoy_->queues->set_acks_in_hardware(0, false);
  buoy_->queues->take_ack_conditions();
  buoy_->queues->receive(command_envelope(3), 1, std::nullopt, 0, 2);
  auto conditions = buoy_->queues->take_ack_conditions();
  ASSERT_EQ(conditions.size(), 1u);
  EXPECT_FALSE(conditions[0]->load());
  EXPECT_EQ(buoy_->custody_held(), 1u);
  EXPECT_EQ(buoy_->forwarder->stats().custody_refused, 2u);
  EXPECT_EQ(buoy_->forwarder->owed_on(0, 1, 100, now), "");
}

}  // namespace
}  // namespace acomms::gateway_test
