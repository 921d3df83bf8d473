// Receipts' bytes (route/receipt.h), the destination's memory of delivered
// identities (route/delivered_identities.h) and the origin's notes of
// wrapped sends (route/end_to_end_ack.h).
#include <gtest/gtest.h>

#include "route/delivered_identities.h"
#include "route/end_to_end_ack.h"
#include "route/envelope.h"
#include "route/receipt.h"

namespace acomms::route {
namespace {

TEST(ReceiptTest, AReceiptIsFiveBytesAndDecodesBack) {
  const std::string bytes = encode_receipt({ReceiptKind::kExpired, 0xbeef}, kDefaultEnvelopeId);
  EXPECT_EQ(bytes, std::string("\xff\xff\x02\xef\xbe", 5));
  EXPECT_EQ(decode_receipt(bytes, kDefaultEnvelopeId), (Receipt{ReceiptKind::kExpired, 0xbeef}));
  // On the air, wrapped: 18 bytes, 144 bits.
  Envelope e;
  e.destination = 1;
  e.payload = bytes;
  EXPECT_EQ(encode_envelope(e, kDefaultEnvelopeId).size() * 8, 144u);
}

TEST(ReceiptTest, WhatIsNotExactlyOneReceiptIsRefused) {
  const std::string good = encode_receipt({ReceiptKind::kDelivered, 3}, kDefaultEnvelopeId);
  EXPECT_FALSE(decode_receipt(good + "x", kDefaultEnvelopeId));
  EXPECT_FALSE(decode_receipt(good.substr(0, 4), kDefaultEnvelopeId));
  EXPECT_FALSE(decode_receipt(good, 300));  // another envelope id
  std::string bad_kind = good;
  bad_kind[2] = 3;
  EXPECT_FALSE(decode_receipt(bad_kind, kDefaultEnvelopeId));
  // A nested envelope's third byte holds its hop limit (>= 16).
  Envelope nested;
  nested.destination = 2;
  nested.payload = "ab";
  EXPECT_FALSE(decode_receipt(encode_envelope(nested, kDefaultEnvelopeId).substr(0, 5), kDefaultEnvelopeId));
}

TEST(DeliveredIdentitiesTest, FullItForgetsTheOneDueFirstNotTheSmallestIdentity) {
  DeliveredIdentities delivered(3);
  delivered.remember({1, 65535}, 100);
  delivered.remember({1, 0}, 200);  // wrapped: the newest is the smallest
  delivered.remember({1, 1}, 300);
  delivered.remember({1, 2}, 400);
  EXPECT_EQ(delivered.size(), 3u);
  EXPECT_FALSE(delivered.contains({1, 65535}, 0));
  EXPECT_TRUE(delivered.contains({1, 0}, 0));
  EXPECT_TRUE(delivered.contains({1, 2}, 0));
}

TEST(DeliveredIdentitiesTest, AnIdentityIsForgottenAfterItsTimeAndARememberMovesIt) {
  DeliveredIdentities delivered;
  delivered.remember({2, 9}, 100);
  EXPECT_TRUE(delivered.contains({2, 9}, 100));
  EXPECT_FALSE(delivered.contains({2, 9}, 100.5));
  delivered.remember({2, 9}, 200);
  delivered.remember({2, 9}, 300);
  EXPECT_TRUE(delivered.contains({2, 9}, 250));
  EXPECT_EQ(delivered.size(), 1u);
}

TEST(EndToEndAcksTest, ANoteIsFoundBySequenceMarkedAtItsHopAckAndTakenByItsReceipt) {
  EndToEndAcks acks(2);
  acks.sent({70000, "net.Command", 3, 2, 10, false, 1000});  // sequence 70000 mod 2^16 = 4464
  EXPECT_FALSE(acks.hop_acked(4464));           // another message of that sequence
  EXPECT_TRUE(acks.hop_acked(70000));
  ASSERT_NE(acks.find(4464), nullptr);
  EXPECT_TRUE(acks.find(4464)->hop_acked);
  acks.sent({5, "net.Command", 3, 2, 20, false, 1000});
  acks.sent({6, "net.Command", 3, 2, 30, false, 1000});  // full: the oldest note goes
  EXPECT_EQ(acks.find(4464), nullptr);
  std::optional<RoutedSend> taken = acks.take(5);
  ASSERT_TRUE(taken);
  EXPECT_EQ(taken->message_id, 5);
  EXPECT_FALSE(acks.take(5));
  EXPECT_EQ(acks.list().size(), 1u);
}

}  // namespace
}  // namespace acomms::route
