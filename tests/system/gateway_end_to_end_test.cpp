// Gateways end to end (the network: gateway_network.h): what a routed
// message's origin hears back from afar (route/receipt.h), and what its
// destination remembers of it across a restart.
//
// Shown: the shore's command reaches the vehicle through the buoy and the
// vehicle's end-to-end ack comes back the same way; the shore's events say
// "acked" (the buoy's hop ack) and, later, "delivered" (the vehicle's); a
// command that expires in the buoy's custody is reported to the shore as
// "expired at node 2"; a vehicle restarted after delivering a command drops
// a copy that arrives afterwards; an envelope hidden inside a delivered
// payload is not acted on.

#include "gateway_network.h"

namespace acomms::gateway_test {
namespace {

using namespace std::chrono_literals;

std::vector<queue::QueueEvent> events_of(const queue::MemoryJournal& journal, int64_t message_id) {
  std::vector<queue::QueueEvent> out;
  for (const queue::QueueEvent& e : journal.events()) {
    if (e.message_id == message_id) out.push_back(e);
  }
  return out;
}

const queue::QueueEvent* first_of(const std::vector<queue::QueueEvent>& events, queue::QueueEventKind kind) {
  for (const queue::QueueEvent& e : events) {
    if (e.kind == kind) return &e;
  }
  return nullptr;
}

TEST_F(GatewayNetwork, TheOriginHearsTheEndToEndAckAndItsEventsTellItFromTheHopAck) {
  build_three();
  shore_->start();
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 417");
  const int64_t id = shore_->queues->find_queue("net.Command")->messages().front().record.id;
  scheduler_.run_for(600s);
  ASSERT_EQ(commands_received(*vehicle_), 1u);

  const std::vector<queue::QueueEvent> events = events_of(shore_journal_, id);
  const queue::QueueEvent* sent = first_of(events, queue::QueueEventKind::kSent);
  const queue::QueueEvent* hop = first_of(events, queue::QueueEventKind::kAcked);
  const queue::QueueEvent* delivered = first_of(events, queue::QueueEventKind::kDelivered);
  ASSERT_NE(sent, nullptr);
  ASSERT_NE(hop, nullptr);
  ASSERT_NE(delivered, nullptr);
  EXPECT_NE(sent->detail.find("to node 3 through node 2"), std::string::npos) << sent->detail;
  EXPECT_NE(hop->detail.find("hop ack from node 2"), std::string::npos) << hop->detail;
  EXPECT_EQ(delivered->detail, "delivered to node 3 (end-to-end ack)");
  EXPECT_EQ(delivered->type, "net.Command");
  EXPECT_EQ(delivered->dest, 3);
  EXPECT_GT(delivered->time, hop->time);  // the far end answers after the first hop
  EXPECT_EQ(shore_->queues->stats("net.Command").delivered, 1u);
  EXPECT_EQ(vehicle_->forwarder->stats().receipts_sent, 1u);
  EXPECT_EQ(shore_->forwarder->stats().receipts_received, 1u);
  EXPECT_TRUE(shore_->forwarder->awaiting_end_to_end().list().empty());
  // The ack went hop by hop with custody, and nothing is left anywhere.
  EXPECT_EQ(buoy_->custody_held() + vehicle_->custody_held(), 0u);
  EXPECT_EQ(buoy_journal_.stored() + vehicle_journal_.stored(), 0u);
}

// The destination got the envelope but handed nothing to its subscribers
// (here it has not loaded the type): no end-to-end ack, so the origin is
// never told the message was delivered.
TEST_F(GatewayNetwork, AMessageTheDestinationCannotDeliverIsNotAckedEndToEnd) {
  build_shore(R"(route { dest: 3 next_hop: 2 link: "sat" })");
  build_buoy("");
  vehicle_ = std::make_unique<GatewayNode>(3, std::vector{status_proto()}, kQueues, "",
                                           std::vector<LinkSpec>{{"acoustic", acoustic_, kAcousticCycle}}, scheduler_,
                                           vehicle_journal_);
  shore_->start();
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 417");
  const int64_t id = shore_->queues->find_queue("net.Command")->messages().front().record.id;
  scheduler_.run_for(600s);
  EXPECT_EQ(commands_received(*vehicle_), 0u);
  const std::vector<queue::QueueEvent> events = events_of(shore_journal_, id);
  EXPECT_NE(first_of(events, queue::QueueEventKind::kAcked), nullptr);  // the first hop has it
  EXPECT_EQ(first_of(events, queue::QueueEventKind::kDelivered), nullptr);
  EXPECT_EQ(vehicle_->forwarder->stats().receipts_sent, 0u);
  EXPECT_EQ(vehicle_->forwarder->stats().delivered, 0u);
  EXPECT_EQ(buoy_->custody_held(), 0u);  // the buoy passed it on
}

TEST_F(GatewayNetwork, AMessageThatExpiresInTheBuoysCustodyIsReportedToItsOriginWithWhere) {
  // net.Command lives 200 s on the shore; the vehicle is off.
  shore_ = std::make_unique<GatewayNode>(
      1, std::vector{status_proto(), command_proto()},
      R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } }
         type { type: "net.Command" policy { ttl_s: 200 } roles { source_field: "src" destination_field: "dest" } })",
      R"(route { dest: 3 next_hop: 2 link: "sat" })", std::vector<LinkSpec>{{"sat", sat_, kSatCycle}}, scheduler_,
      shore_journal_);
  build_buoy("route { dest: 3 next_hop: 3 link: \"acoustic\" }");
  shore_->start();
  buoy_->start();
  shore_->submit("net.Command", "src: 1 dest: 3 code: 5");
  const int64_t id = shore_->queues->find_queue("net.Command")->messages().front().record.id;
  scheduler_.run_for(100s);
  ASSERT_EQ(buoy_->custody_held(), 1u);
  // Handed on, not yet delivered: the shore knows it is with its next hop.
  std::vector<route::RoutedSend> waiting = shore_->forwarder->awaiting_end_to_end().list();
  ASSERT_EQ(waiting.size(), 1u);
  EXPECT_EQ(waiting.front().message_id, id);
  EXPECT_TRUE(waiting.front().hop_acked);
  EXPECT_EQ(waiting.front().next_hop, 2);
  scheduler_.run_for(500s);

  EXPECT_EQ(buoy_->custody_held(), 0u);
  EXPECT_EQ(buoy_->forwarder->stats().receipts_sent, 1u);
  const std::vector<queue::QueueEvent> events = events_of(shore_journal_, id);
  const queue::QueueEvent* expired = first_of(events, queue::QueueEventKind::kExpired);
  ASSERT_NE(expired, nullptr);
  EXPECT_EQ(expired->detail, "expired at node 2");
  EXPECT_EQ(first_of(events, queue::QueueEventKind::kDelivered), nullptr);
  EXPECT_EQ(shore_->forwarder->stats().receipts_received, 1u);
  EXPECT_TRUE(shore_->forwarder->awaiting_end_to_end().list().empty());
}

TEST_F(GatewayNetwork, AVehicleRestartedAfterDeliveringACommandDropsACopyThatComesLater) {
  build_three();
  shore_->start();
  buoy_->start();
  vehicle_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 5");
  const int64_t id = shore_->queues->find_queue("net.Command")->messages().front().record.id;
  scheduler_.run_for(300s);
  ASSERT_EQ(commands_received(*vehicle_), 1u);
  const std::string payload = vehicle_->received.front().encoded;
  // The vehicle dies and comes back from its store.
  vehicle_.reset();
  build_vehicle();
  route::Envelope copy;
  copy.origin = 1;
  copy.destination = 3;
  copy.seq = static_cast<uint16_t>(id & 0xffff);
  copy.hops = 2;
  copy.ttl_s = 1000;
  copy.payload = payload;
  const std::string frame = route::encode_envelope(copy, route::kDefaultEnvelopeId);
  EXPECT_TRUE(vehicle_->queues->receive(frame, 2, std::nullopt, 0, 3).empty());
  EXPECT_EQ(vehicle_->forwarder->stats().duplicates, 1u);
  EXPECT_EQ(vehicle_->forwarder->stats().delivered, 0u);
}

TEST_F(GatewayNetwork, AnEnvelopeInsideADeliveredPayloadIsNotActedOn) {
  build_three();
  // A status for the vehicle, and behind it in the same payload an
  // envelope for node 9 that the vehicle would otherwise take into custody.
  auto status = vehicle_->codec.new_message("net.Status");
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString("src: 1 dest: 3 battery: 50", status.get()));
  route::Envelope inner;
  inner.origin = 1;
  inner.destination = 9;
  inner.seq = 7;
  inner.ttl_s = 1000;
  inner.payload = "x";
  route::Envelope outer;
  outer.origin = 1;
  outer.destination = 3;
  outer.seq = 8;
  outer.ttl_s = 1000;
  outer.payload = vehicle_->codec.encode(*status) + route::encode_envelope(inner, route::kDefaultEnvelopeId);
  const std::string frame = route::encode_envelope(outer, route::kDefaultEnvelopeId);
  vehicle_->queues->receive(frame, 2, std::nullopt, 0, 3);
  EXPECT_EQ(vehicle_->forwarder->stats().custody_taken, 0u);
  EXPECT_EQ(vehicle_->forwarder->stats().malformed, 1u);
  // The outer envelope was delivered: the vehicle holds only its ack.
  EXPECT_EQ(vehicle_->forwarder->stats().receipts_sent, 1u);
  ASSERT_EQ(vehicle_->custody_held(), 1u);
  // What queue ls shows of it: an end-to-end ack about message 8.
  const queue::Queue* custody = vehicle_->queues->find_queue("acomms.route.Custody.v10");
  ASSERT_NE(custody, nullptr);
  const std::string json = vehicle_->forwarder->custody_json(*custody, custody->messages().front());
  EXPECT_NE(json.find(R"("destination":1,)"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("receipt":"delivered","about_seq":8)"), std::string::npos) << json;
}

}  // namespace
}  // namespace acomms::gateway_test
