// Gateways with auth configured (route/receipt_seal.h): receipts are sealed
// by the node that reports, and an unsealed or forged one changes nothing.
// Before, anyone with a modem could tell the shore its command was
// delivered, or tell it that the buoy had taken custody.

#include "dccl/message_auth.h"
#include "gateway_network.h"

namespace acomms::gateway_test {
namespace {

using namespace std::chrono_literals;

dccl::Keyring keyring(char fill) {
  dccl::Keyring ring;
  ring.keys[1].key = std::string(16, fill);
  ring.sign_id = 1;
  return ring;
}

// Node `id` seals as itself with the fleet's key (`fill` 'k') or another.
std::shared_ptr<dccl::MessageAuthenticator> sealer(int32_t id, char fill = 'k') {
  return std::make_shared<dccl::MessageAuthenticator>(32, keyring(fill), id);
}

void authenticate(GatewayNode& node, int32_t id) { node.codec.set_authentication(sealer(id), {}); }

// A "delivered" receipt from node 3 for the shore's message `seq`,
// sealed by `seal` (null: not at all), as the buoy would hand it over.
std::string delivered_envelope(uint16_t seq, const dccl::MessageAuthenticator* seal, double now) {
  route::Envelope e;
  e.origin = 3;
  e.destination = 1;
  e.seq = 900;
  e.ttl_s = 1000;
  e.payload = route::encode_receipt({route::ReceiptKind::kDelivered, seq}, route::kDefaultEnvelopeId);
  if (seal != nullptr) seal->seal(e.payload, now);
  return route::encode_envelope(e, route::kDefaultEnvelopeId);
}

TEST_F(GatewayNetwork, WithAuthAForgedEndToEndAckIsRefusedAndTheSealedOneCounts) {
  build_three();
  authenticate(*shore_, 1);
  authenticate(*buoy_, 2);
  authenticate(*vehicle_, 3);
  shore_->start();
  buoy_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 12");
  scheduler_.run_for(120s);  // with the buoy; the vehicle is off
  ASSERT_EQ(shore_->forwarder->awaiting_end_to_end().list().size(), 1u);
  const uint16_t seq = static_cast<uint16_t>(shore_->forwarder->awaiting_end_to_end().list().front().message_id);
  const double now = scheduler_.clock().now_seconds();

  // Unsealed, and sealed under a key the fleet does not have.
  shore_->queues->receive(delivered_envelope(seq, nullptr, now), 2, std::nullopt, 0, 1);
  shore_->queues->receive(delivered_envelope(seq, sealer(3, 'x').get(), now), 2, std::nullopt, 0, 1);
  // Sealed with the fleet's key, but by the buoy, not the destination.
  shore_->queues->receive(delivered_envelope(seq, sealer(2).get(), now), 2, std::nullopt, 0, 1);
  EXPECT_EQ(shore_->forwarder->stats().receipts_refused, 3u);
  EXPECT_EQ(shore_->forwarder->stats().receipts_received, 0u);
  EXPECT_EQ(shore_->forwarder->awaiting_end_to_end().list().size(), 1u) << "still awaiting the real one";

  vehicle_->start();
  scheduler_.run_for(600s);
  EXPECT_EQ(commands_received(*vehicle_), 1u);
  EXPECT_EQ(shore_->forwarder->stats().receipts_received, 1u) << "the vehicle's sealed ack went through the buoy";
  EXPECT_EQ(shore_->forwarder->stats().receipts_refused, 3u);
  EXPECT_TRUE(shore_->forwarder->awaiting_end_to_end().list().empty());
}

TEST_F(GatewayNetwork, WithAuthCustodyReceiptsAreSealedAndAnUnsealedOneIsRefused) {
  build_shore(R"(route { dest: 3 next_hop: 2 link: "sat" })");
  build_buoy("");
  authenticate(*shore_, 1);
  authenticate(*buoy_, 2);
  buoy_->queues->set_acks_in_hardware(0, true);
  shore_->queues->set_acks_in_hardware(0, true);
  route::Envelope e;
  e.origin = 1;
  e.destination = 3;
  e.seq = 4;
  e.ttl_s = 1000;
  e.payload = "opaque";
  buoy_->queues->receive(route::encode_envelope(e, route::kDefaultEnvelopeId), 1, std::nullopt, 0, 2);
  const double now = scheduler_.clock().now_seconds();
  const std::string sealed = buoy_->forwarder->owed_on(0, 1, 100, now);
  ASSERT_EQ(sealed.size(), route::kCustodyReceiptBytes + sealer(2)->trailer_bytes()) << "7 bytes and a trailer";
  const std::string bare =
      route::encode_custody_receipt({route::CustodyVerdict::kTaken, {1, 4}}, route::kDefaultEnvelopeId);
  shore_->queues->receive(bare, 2, std::nullopt, 0, 1);
  EXPECT_EQ(shore_->forwarder->stats().receipts_refused, 1u);
  shore_->queues->receive(sealed, 2, std::nullopt, 0, 1);  // verifies; nothing waits for it here
  EXPECT_EQ(shore_->forwarder->stats().receipts_refused, 1u);
  EXPECT_EQ(shore_->forwarder->stats().custody_receipts_ignored, 1u);
  shore_->queues->receive(sealed, 3, std::nullopt, 0, 1);  // the buoy's seal, another node's transmission
  EXPECT_EQ(shore_->forwarder->stats().receipts_refused, 2u);
}

}  // namespace
}  // namespace acomms::gateway_test
