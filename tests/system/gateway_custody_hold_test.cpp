// Gateways: what a message held for a custody receipt (route/custody_
// receipt.h) must not do, driven frame by frame (build_frames, on_ack) on
// a simulated clock. Each test is a defect a review found:
//  - a held message went out again as plain DCCL when its destination
//    became a neighbour, while the next hop passed its copy on: delivered
//    twice; and a plain send's modem ACK found a stale wrapped-send note
//    and held the message for a receipt that never comes;
//  - a frame of owed receipts only made its transmission a broadcast, but
//    a later frame of it took a unicast message that awaited an ACK the
//    transmission never asked for (sent again: delivered twice);
//  - a custody message whose ttl ran out while held for the next hop's
//    receipt was reported "expired" to its origin, which then forgot it
//    (its real end-to-end ack ignored, a resend delivered twice);
//  - a refusal doubled the back-off a second time for the same offer.

#include "gateway_network.h"

namespace acomms::gateway_test {
namespace {

using namespace std::chrono_literals;

std::string envelope_for(uint16_t dest, uint16_t seq, uint32_t ttl_s) {
  route::Envelope e;
  e.origin = 1;
  e.destination = dest;
  e.seq = seq;
  e.ttl_s = ttl_s;
  e.payload = "opaque";
  return route::encode_envelope(e, route::kDefaultEnvelopeId);
}

queue::DataRequest request_on(int link, uint32_t bytes, uint32_t frames = 1) {
  queue::DataRequest request;
  request.link = link;
  request.max_frame_bytes = bytes;
  request.max_num_frames = frames;
  request.ack_requested = true;
  return request;
}

class CustodyHold : public GatewayNetwork {
 protected:
  double now() const { return scheduler_.clock().now_seconds(); }
  size_t queued(GatewayNode& node, const std::string& type) { return node.queues->find_queue(type)->size(); }
};

TEST_F(CustodyHold, AMessageHeldForAReceiptDoesNotGoPlainToADestinationThatBecameANeighbour) {
  build_shore("");
  shore_->queues->set_acks_in_hardware(0, true);
  shore_->forwarder->routes().heard(2, "sat", now(), true);
  shore_->forwarder->routes().heard_through(3, 2, "sat", now());
  shore_->submit("net.Command", "src: 1 dest: 3 code: 4");
  std::vector<queue::Frame> frames = shore_->queues->build_frames(request_on(0, 64));
  ASSERT_EQ(frames.size(), 1u);
  ASSERT_EQ(frames[0].dest, 2) << "wrapped for the buoy";
  shore_->queues->on_ack(frames[0].frame_id);  // the buoy's modem
  ASSERT_EQ(shore_->forwarder->held_for_receipt().size(), 1u);

  // The vehicle is heard directly now: a neighbour.
  for (int i = 0; i < 3; ++i) shore_->forwarder->routes().heard(3, "sat", now(), true);
  ASSERT_EQ(shore_->forwarder->next_hop(3)->node, 3);
  scheduler_.run_for(60s);
  frames = shore_->queues->build_frames(request_on(0, 64));
  EXPECT_TRUE(frames.empty()) << "held for the buoy's receipt: not sent again in any form";
  EXPECT_EQ(queued(*shore_, "net.Command"), 1u);
}

TEST_F(CustodyHold, APlainSendAfterAnUnackedWrappedOneIsEndedByItsModemAck) {
  build_shore("");
  shore_->queues->set_acks_in_hardware(0, true);
  shore_->forwarder->routes().heard(2, "sat", now(), true);
  shore_->forwarder->routes().heard_through(3, 2, "sat", now());
  shore_->submit("net.Command", "src: 1 dest: 3 code: 4");
  std::vector<queue::Frame> frames = shore_->queues->build_frames(request_on(0, 64));
  ASSERT_EQ(frames.size(), 1u);
  ASSERT_EQ(frames[0].dest, 2);
  // No ACK: released at the next request. The vehicle is a neighbour now.
  for (int i = 0; i < 3; ++i) shore_->forwarder->routes().heard(3, "sat", now(), true);
  frames = shore_->queues->build_frames(request_on(0, 64));
  ASSERT_EQ(frames.size(), 1u);
  ASSERT_EQ(frames[0].dest, 3) << "plain, to the vehicle";
  shore_->queues->on_ack(frames[0].frame_id);  // the vehicle's modem: delivered
  EXPECT_EQ(queued(*shore_, "net.Command"), 0u) << "not held for a receipt no node will send";
  EXPECT_TRUE(shore_->forwarder->held_for_receipt().empty());
}

TEST_F(CustodyHold, ATransmissionOfOwedReceiptsOnlyTakesNoMessageThatWouldAwaitAnAck) {
  build_buoy("");
  buoy_->queues->set_acks_in_hardware(0, true);  // "sat"
  buoy_->queues->receive(envelope_for(3, 1, 1000), 1, std::nullopt, 0, 2);
  ASSERT_EQ(buoy_->custody_held(), 1u);  // no route to 3: it stays; a "taken" receipt is owed to 1
  buoy_->forwarder->routes().heard(1, "sat", now(), true);
  buoy_->submit("net.Status", "src: 2 dest: 1 battery: 5");
  const size_t status = buoy_->queues->find_queue("net.Status")->messages().front().encoded.size();
  // Frame 0 has room for the receipt, not for the status as well.
  std::vector<queue::Frame> frames =
      buoy_->queues->build_frames(request_on(0, static_cast<uint32_t>(route::kCustodyReceiptBytes + status - 1), 2));
  ASSERT_FALSE(frames.empty());
  ASSERT_EQ(frames[0].bytes.size(), route::kCustodyReceiptBytes) << "the receipt only";
  for (const queue::Frame& frame : frames) {
    EXPECT_EQ(frame.dest, frames.front().dest) << "one transmission, one destination";
    if (frames.front().dest == queue::kBroadcast) {
      EXPECT_FALSE(frame.ack_requested) << "a broadcast is never ACKed";
    }
  }
  const queue::Queue& statuses = *buoy_->queues->find_queue("net.Status");
  ASSERT_EQ(statuses.size(), 1u);
  EXPECT_EQ(statuses.in_flight(), 0u) << "it goes in the next transmission, to its node";
}

TEST_F(CustodyHold, CustodyWhoseTtlRunsOutAwaitingTheNextHopsReceiptIsNotReportedExpired) {
  build_buoy(R"(route { dest: 3 next_hop: 4 link: "acoustic" } route { dest: 1 next_hop: 1 link: "sat" })");
  buoy_->queues->set_acks_in_hardware(1, true);  // "acoustic": its modem ACKs
  buoy_->queues->receive(envelope_for(3, 7, 300), 1, std::nullopt, 0, 2);
  ASSERT_EQ(buoy_->custody_held(), 1u);
  std::vector<queue::Frame> frames = buoy_->queues->build_frames(request_on(1, 64));
  ASSERT_EQ(frames.size(), 1u);
  ASSERT_EQ(frames[0].dest, 4);
  buoy_->queues->on_ack(frames[0].frame_id);  // node 4's modem
  ASSERT_EQ(buoy_->forwarder->held_for_receipt().size(), 1u);

  scheduler_.run_for(400s);  // its ttl runs out before the receipt's wait
  buoy_->queues->build_frames(request_on(1, 64));
  EXPECT_EQ(buoy_->custody_held(), 0u);
  EXPECT_EQ(buoy_->forwarder->stats().expired_awaiting_receipt, 1u);
  EXPECT_EQ(buoy_->forwarder->stats().receipts_sent, 0u) << "no expiry report: node 4 most likely holds it";
}

TEST_F(CustodyHold, CustodyThatExpiresWithNoAckIsReportedExpired) {
  // The same without the modem's ACK: an expiry here is real.
  build_buoy(R"(route { dest: 3 next_hop: 4 link: "acoustic" } route { dest: 1 next_hop: 1 link: "sat" })");
  buoy_->queues->set_acks_in_hardware(1, true);
  buoy_->queues->receive(envelope_for(3, 7, 300), 1, std::nullopt, 0, 2);
  ASSERT_EQ(buoy_->queues->build_frames(request_on(1, 64)).size(), 1u);
  scheduler_.run_for(400s);
  buoy_->queues->build_frames(request_on(1, 64));
  EXPECT_EQ(buoy_->custody_held(), 1u) << "the expiry report, in custody for node 1";
  EXPECT_EQ(buoy_->forwarder->stats().receipts_sent, 1u);
  EXPECT_EQ(buoy_->forwarder->stats().expired_awaiting_receipt, 0u);
}

TEST_F(CustodyHold, ARefusalDoesNotDoubleTheBackOffOfTheOfferItAnswers) {
  build_shore("");
  shore_->queues->set_acks_in_hardware(0, true);
  shore_->forwarder->routes().heard(2, "sat", now(), true);
  shore_->forwarder->routes().heard_through(3, 2, "sat", now());
  shore_->submit("net.Command", "src: 1 dest: 3 code: 4");
  std::vector<queue::Frame> frames = shore_->queues->build_frames(request_on(0, 64));
  ASSERT_EQ(frames.size(), 1u);
  shore_->queues->on_ack(frames[0].frame_id);
  ASSERT_EQ(shore_->forwarder->held_for_receipt().size(), 1u);
  const route::MessageIdentity about = shore_->forwarder->held_for_receipt().begin()->second.identity;
  shore_->queues->receive(
      route::encode_custody_receipt({route::CustodyVerdict::kRefused, about}, route::kDefaultEnvelopeId), 2,
      std::nullopt, 0, 1);
  ASSERT_TRUE(shore_->forwarder->held_for_receipt().begin()->second.refused);
  EXPECT_DOUBLE_EQ(shore_->forwarder->held_for_receipt().begin()->second.until - now(),
                   route::Forwarder::receipt_wait_s(1))
      << "first offer refused: the first wait, from the refusal";

  // The second offer, ACKed and refused: one doubling.
  scheduler_.run_for(std::chrono::seconds(static_cast<int64_t>(route::Forwarder::receipt_wait_s(1)) + 10));
  frames = shore_->queues->build_frames(request_on(0, 64));
  ASSERT_EQ(frames.size(), 1u);
  shore_->queues->on_ack(frames[0].frame_id);
  shore_->queues->receive(
      route::encode_custody_receipt({route::CustodyVerdict::kRefused, about}, route::kDefaultEnvelopeId), 2,
      std::nullopt, 0, 1);
  EXPECT_DOUBLE_EQ(shore_->forwarder->held_for_receipt().begin()->second.until - now(),
                   route::Forwarder::receipt_wait_s(2));
  EXPECT_EQ(route::Forwarder::receipt_wait_s(2), 2 * route::Forwarder::receipt_wait_s(1));
}

TEST_F(CustodyHold, ANoteOfAMessageInFlightOutlivesThousandsOfOtherWrappedSends) {
  // Custody for 3 goes on "acoustic" through node 4; the buoy's own
  // statuses for node 9 go wrapped on "sat" through node 1, unacked.
  build_buoy(R"(route { dest: 3 next_hop: 4 link: "acoustic" } route { dest: 9 next_hop: 1 link: "sat" })");
  buoy_->queues->set_acks_in_hardware(1, true);
  buoy_->queues->receive(envelope_for(3, 7, 3000), 1, std::nullopt, 0, 2);
  std::vector<queue::Frame> in_flight = buoy_->queues->build_frames(request_on(1, 64));
  ASSERT_EQ(in_flight.size(), 1u);
  queue::DataRequest flood = request_on(0, 64, 8);
  flood.ack_requested = false;
  for (int i = 0; i < 5000; ++i) {
    buoy_->submit("net.Status", "src: 2 dest: 9 battery: 1");
    if (i % 20 == 19) ASSERT_FALSE(buoy_->queues->build_frames(flood).empty());
  }
  buoy_->queues->on_ack(in_flight[0].frame_id);  // node 4's modem, at last
  EXPECT_EQ(buoy_->forwarder->held_for_receipt().size(), 1u) << "held for node 4's receipt, not forgotten";
  EXPECT_EQ(buoy_->custody_held(), 1u);
}

TEST_F(CustodyHold, OwedReceiptsAreBoundedDroppingRefusedOnesNeverATakenOne) {
  build_buoy("max_custody: 1");
  buoy_->queues->set_acks_in_hardware(0, true);
  buoy_->queues->receive(envelope_for(3, 1, 1000), 1, std::nullopt, 0, 2);  // taken
  for (uint16_t seq = 2; seq < 1500; ++seq) buoy_->queues->receive(envelope_for(3, seq, 1000), 1, std::nullopt, 0, 2);
  EXPECT_EQ(buoy_->custody_held(), 1u);
  EXPECT_GT(buoy_->forwarder->stats().custody_receipts_dropped, 0u);
  std::string owed;
  for (std::string bytes; !(bytes = buoy_->forwarder->owed_on(0, 1, 700, now())).empty();) owed += bytes;
  EXPECT_LE(owed.size(), 1024 * route::kCustodyReceiptBytes);
  EXPECT_EQ(owed.substr(0, route::kCustodyReceiptBytes),
            route::encode_custody_receipt({route::CustodyVerdict::kTaken, {1, 1}}, route::kDefaultEnvelopeId))
      << "the taken one is kept";
}

}  // namespace
}  // namespace acomms::gateway_test
