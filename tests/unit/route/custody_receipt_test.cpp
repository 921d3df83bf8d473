// Custody receipts' bytes (route/custody_receipt.h): what a gateway says to
// the previous hop on a link whose modem ACKs, and the wait before a
// message is offered again.
#include <gtest/gtest.h>

#include "route/custody_receipt.h"
#include "route/envelope.h"
#include "route/forwarder.h"

namespace acomms::route {
namespace {

TEST(CustodyReceiptTest, AReceiptIsSevenBytesFiftySixBitsAndDecodesBack) {
  const CustodyReceipt taken{CustodyVerdict::kTaken, {0x0102, 0xbeef}};
  const std::string bytes = encode_custody_receipt(taken, kDefaultEnvelopeId);
  EXPECT_EQ(bytes, std::string("\xff\xff\x03\x02\x01\xef\xbe", 7));
  EXPECT_EQ(bytes.size() * 8, 56u);
  EXPECT_EQ(decode_custody_receipt(bytes, kDefaultEnvelopeId), taken);
  const CustodyReceipt refused{CustodyVerdict::kRefused, {7, 9}};
  EXPECT_EQ(decode_custody_receipt(encode_custody_receipt(refused, 300), 300), refused);
}

TEST(CustodyReceiptTest, NeitherAnEnvelopeNorAShortOrForeignReceiptIsTakenForOne) {
  const std::string good = encode_custody_receipt({CustodyVerdict::kTaken, {1, 2}}, kDefaultEnvelopeId);
  EXPECT_FALSE(decode_custody_receipt(good.substr(0, 6), kDefaultEnvelopeId));
  EXPECT_FALSE(decode_custody_receipt(good, 300));  // another envelope id
  std::string other = good;
  other[2] = 1;  // an end-to-end receipt's kind, never a custody verdict
  EXPECT_FALSE(starts_custody_receipt(other, kDefaultEnvelopeId));
  // Every envelope's third byte has its hop limit (1-15) in the high nibble.
  Envelope e;
  e.destination = 3;
  e.payload = "x";
  for (uint8_t limit = 1; limit <= kMaxHopLimit; ++limit) {
    e.hop_limit = limit;
    EXPECT_FALSE(starts_custody_receipt(encode_envelope(e, kDefaultEnvelopeId), kDefaultEnvelopeId));
  }
  // What follows a receipt in a frame is not its business.
  EXPECT_TRUE(decode_custody_receipt(good + "more", kDefaultEnvelopeId));
}

TEST(CustodyReceiptTest, TheWaitForAReceiptDoublesFromTenMinutesToAnHour) {
  EXPECT_EQ(Forwarder::receipt_wait_s(1), 600);
  EXPECT_EQ(Forwarder::receipt_wait_s(2), 1200);
  EXPECT_EQ(Forwarder::receipt_wait_s(3), 2400);
  EXPECT_EQ(Forwarder::receipt_wait_s(4), 3600);
  EXPECT_EQ(Forwarder::receipt_wait_s(1000), 3600);
}

}  // namespace
}  // namespace acomms::route
