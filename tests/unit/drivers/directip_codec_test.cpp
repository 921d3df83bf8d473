// The DirectIP codec (plugins/drivers/iridium_shore/direct_ip.h) against
// the exact bytes of ../shared/spec/iridium-sbd.md §9: the worked MO
// (§9.2.5), MT and confirmation (§9.3.5) examples, and every way an MO
// from the network can be wrong.

#include "iridium_shore/direct_ip.h"

#include <gtest/gtest.h>

#include <initializer_list>

namespace acomms::drivers::directip {
namespace {

const std::string kImei = "300234010000001";

std::string bytes(std::initializer_list<int> values) {
  std::string out;
  for (int v : values) out.push_back(static_cast<char>(v));
  return out;
}

// Spec §9.2.5, byte for byte.
std::string worked_mo() {
  return bytes({0x01, 0x00, 0x33,                                  //
                0x01, 0x00, 0x1c, 0x00, 0x01, 0xe2, 0x40}) +       // header IE, CDR 123456
         kImei +                                                   //
         bytes({0x00, 0x04, 0xd2, 0x00, 0x00, 0x65, 0x53, 0xf1, 0x00,  // status, MOMSN, MTMSN, time
                0x03, 0x00, 0x0b, 0x03, 0x0c, 0x87, 0x07, 0x2d, 0x1a, 0x85, 0x00, 0x00, 0x00, 0x03,
                0x02, 0x00, 0x03, 0x41, 0x42, 0x43});
}

// An MO with `ies` after the prefix (the overall length computed).
std::string mo_with(const std::string& ies) {
  return bytes({0x01, static_cast<int>(ies.size() >> 8), static_cast<int>(ies.size() & 0xff)}) + ies;
}
std::string header_ie(int status = 0) {
  return bytes({0x01, 0x00, 0x1c, 0x00, 0x00, 0x00, 0x09}) + kImei +
         bytes({status, 0x00, 0x05, 0x00, 0x00, 0x65, 0x53, 0xf1, 0x00});
}
std::string payload_ie(const std::string& payload) {
  return bytes({0x02, static_cast<int>(payload.size() >> 8), static_cast<int>(payload.size() & 0xff)}) + payload;
}

TEST(DirectIpMoTest, ParsesTheSpecsWorkedExample) {
  std::string error;
  auto mo = parse_mo(worked_mo(), &error);
  ASSERT_TRUE(mo) << error;
  EXPECT_EQ(mo->header.cdr_reference, 123456u);
  EXPECT_EQ(mo->header.imei, kImei);
  EXPECT_EQ(mo->header.session_status, 0);
  EXPECT_EQ(mo->header.momsn, 1234);
  EXPECT_EQ(mo->header.mtmsn, 0);
  EXPECT_EQ(mo->header.session_time, 1700000000u);
  EXPECT_EQ(mo->payload, "ABC");
  ASSERT_TRUE(mo->location);
  EXPECT_DOUBLE_EQ(mo->location->latitude_deg, -(12 + 34567 / 60000.0));   // south
  EXPECT_DOUBLE_EQ(mo->location->longitude_deg, -(45 + 6789 / 60000.0));   // west
  EXPECT_EQ(mo->location->cep_km, 3u);
  EXPECT_EQ(mo->unknown_ies, 0u);
}

TEST(DirectIpMoTest, UnknownIeIsSkippedByItsLengthAndCounted) {
  std::string error;
  auto mo = parse_mo(mo_with(bytes({0x7f, 0x00, 0x02, 0x02, 0x00}) + header_ie() + payload_ie("xy")), &error);
  ASSERT_TRUE(mo) << error;
  EXPECT_EQ(mo->unknown_ies, 1u);
  EXPECT_EQ(mo->payload, "xy");  // the unknown IE's bytes (which look like a payload IE) were not read as one
  EXPECT_EQ(mo->header.momsn, 5);
}

TEST(DirectIpMoTest, RefusesAnOverallLengthThatDoesNotMatch) {
  std::string error;
  std::string mo = worked_mo();
  EXPECT_FALSE(parse_mo(mo.substr(0, mo.size() - 1), &error));
  EXPECT_EQ(error, "overall length says 51 bytes follow, 50 do");
  EXPECT_FALSE(parse_mo(mo + "x", &error));
  EXPECT_EQ(error, "overall length says 51 bytes follow, 52 do");
}

TEST(DirectIpMoTest, RefusesAnIeLongerThanWhatIsLeft) {
  std::string error;
  std::string ies = header_ie() + bytes({0x02, 0x00, 0x09, 'a', 'b'});
  EXPECT_FALSE(parse_mo(mo_with(ies), &error));
  EXPECT_EQ(error, "IE 0x02 claims 9 bytes, 2 are left");
  EXPECT_FALSE(parse_mo(mo_with(header_ie() + bytes({0x02, 0x00})), &error));
  EXPECT_EQ(error, "an IE header at offset 34 is cut off (2 bytes are left)");
}

TEST(DirectIpMoTest, RefusesAHeaderOfTheWrongLength) {
  std::string error;
  std::string short_header = header_ie();
  short_header[2] = 0x1b;
  short_header.pop_back();
  EXPECT_FALSE(parse_mo(mo_with(short_header), &error));
  EXPECT_EQ(error, "MO header IE 0x01 has 27 bytes, not 28");
}

TEST(DirectIpMoTest, RefusesAPayloadAboveThe9603Limit) {
  std::string error;
  EXPECT_TRUE(parse_mo(mo_with(header_ie() + payload_ie(std::string(340, 'p'))), &error)) << error;
  EXPECT_FALSE(parse_mo(mo_with(header_ie() + payload_ie(std::string(341, 'p'))), &error));
  EXPECT_EQ(error, "MO payload of 341 bytes is above the 9602/9603 limit of 340");
}

TEST(DirectIpMoTest, RefusesABadPrefix) {
  std::string error;
  std::string mo = worked_mo();
  mo[0] = 2;
  EXPECT_FALSE(parse_mo(mo, &error));
  EXPECT_EQ(error, "protocol revision 2, expected 1");
  EXPECT_FALSE(parse_prefix(bytes({0x01, 0x08, 0x01}), &error));
  EXPECT_EQ(error, "overall length 2049 is above the limit of 2048");
  EXPECT_EQ(parse_prefix(bytes({0x01, 0x08, 0x00}), &error), 2048);
  EXPECT_FALSE(parse_mo(bytes({0x01, 0x00}), &error));
}

TEST(DirectIpMoTest, RefusesAMissingOrRepeatedHeaderAndARepeatedPayload) {
  std::string error;
  EXPECT_FALSE(parse_mo(mo_with(payload_ie("x")), &error));
  EXPECT_EQ(error, "no MO header IE (0x01)");
  EXPECT_FALSE(parse_mo(mo_with(header_ie() + header_ie()), &error));
  EXPECT_EQ(error, "a second MO header IE");
  EXPECT_FALSE(parse_mo(mo_with(header_ie() + payload_ie("a") + payload_ie("b")), &error));
  EXPECT_EQ(error, "a second MO payload IE");
}

TEST(DirectIpMoTest, RefusesAnImeiThatIsNotDigits) {
  std::string error;
  std::string header = header_ie();
  header[7] = 'X';
  EXPECT_FALSE(parse_mo(mo_with(header), &error));
  EXPECT_EQ(error, "MO header's IMEI is not 15 ASCII digits");
}

TEST(DirectIpMoTest, ALocationOfAnotherLengthIsSkippedNotFatal) {
  // SBD-DG's table prints 20 for the location IE; real messages use 11.
  std::string error;
  auto mo = parse_mo(mo_with(header_ie() + bytes({0x03, 0x00, 0x14}) + std::string(20, '\0') + payload_ie("p")),
                     &error);
  ASSERT_TRUE(mo) << error;
  EXPECT_FALSE(mo->location);
  EXPECT_EQ(mo->unusable_locations, 1u);
  EXPECT_EQ(mo->payload, "p");
  // Minutes out of range (60000 thousandths) are not a location either.
  mo = parse_mo(mo_with(header_ie() + bytes({0x03, 0x00, 0x0b, 0, 10, 0xea, 0x60, 10, 0, 0, 0, 0, 0, 1})), &error);
  ASSERT_TRUE(mo) << error;
  EXPECT_FALSE(mo->location);
}

TEST(DirectIpMoTest, AFailedSessionCarriesNoPayload) {
  std::string error;
  auto mo = parse_mo(mo_with(header_ie(13)), &error);
  ASSERT_TRUE(mo) << error;
  EXPECT_EQ(mo->header.session_status, 13);
  EXPECT_TRUE(mo->payload.empty());
  EXPECT_FALSE(mo_session_succeeded(13));
  EXPECT_FALSE(mo_session_succeeded(10));
  EXPECT_TRUE(mo_session_succeeded(0));
  EXPECT_TRUE(mo_session_succeeded(2));
}

TEST(DirectIpMoTest, ConfirmationBytesAreTheSpecs) {
  EXPECT_EQ(build_mo_confirmation(true), bytes({0x01, 0x00, 0x04, 0x05, 0x00, 0x01, 0x01}));
  EXPECT_EQ(build_mo_confirmation(false), bytes({0x01, 0x00, 0x04, 0x05, 0x00, 0x01, 0x00}));
}

TEST(DirectIpMtTest, BuildsTheSpecsWorkedExample) {
  std::string error;
  MtSubmission mt{.client_id = 7, .imei = kImei, .flags = 0, .payload = bytes({0x01, 0x02})};
  EXPECT_EQ(build_mt(mt, &error), bytes({0x01, 0x00, 0x1d, 0x41, 0x00, 0x15, 0x00, 0x00, 0x00, 0x07}) + kImei +
                                      bytes({0x00, 0x00, 0x42, 0x00, 0x02, 0x01, 0x02}))
      << error;
  mt.flags = kAssignMtmsn | kFlushMtQueue;
  std::string built = build_mt(mt, &error);
  EXPECT_EQ(built.substr(25, 2), bytes({0x00, 0x21}));
}

TEST(DirectIpMtTest, RefusesWhatTheGatewayWouldRefuse) {
  std::string error;
  MtSubmission mt{.client_id = 7, .imei = kImei, .flags = 0, .payload = std::string(270, 'x')};
  EXPECT_EQ(build_mt(mt, &error).size(), 3u + 24u + 3u + 270u);
  mt.payload += 'x';
  EXPECT_EQ(build_mt(mt, &error), "");
  EXPECT_EQ(error, "MT payload of 271 bytes is above the limit of 270");
  mt.payload = "x";
  mt.imei = "30023401000000";
  EXPECT_EQ(build_mt(mt, &error), "");
  EXPECT_EQ(error, "IMEI \"30023401000000\" is not 15 ASCII digits");
  mt.imei = kImei;
  mt.flags = kAssignMtmsn;
  mt.client_id = 65536;
  EXPECT_EQ(build_mt(mt, &error), "");
  mt.client_id = 0;
  EXPECT_EQ(build_mt(mt, &error), "");
  mt.flags = 0;
  mt.payload = "";
  EXPECT_EQ(build_mt(mt, &error), "");
  EXPECT_EQ(error, "an MT needs a payload of 1 byte or more");
  mt.flags = kSendRingAlert;
  EXPECT_EQ(build_mt(mt, &error), bytes({0x01, 0x00, 0x18, 0x41, 0x00, 0x15, 0x00, 0x00, 0x00, 0x00}) + kImei +
                                      bytes({0x00, 0x02}));
}

std::string confirmation(std::initializer_list<int> auto_id_and_status) {
  return bytes({0x01, 0x00, 0x1c, 0x44, 0x00, 0x19, 0x00, 0x00, 0x00, 0x07}) + kImei + bytes(auto_id_and_status);
}

TEST(DirectIpMtTest, ParsesTheSpecsConfirmationAndARefusal) {
  std::string error;
  auto c = parse_mt_confirmation(confirmation({0x00, 0x0f, 0x12, 0x06, 0x00, 0x01}), &error);
  ASSERT_TRUE(c) << error;
  EXPECT_EQ(c->client_id, 7u);
  EXPECT_EQ(c->imei, kImei);
  EXPECT_EQ(c->auto_id, 987654u);
  EXPECT_EQ(c->status, 1);
  EXPECT_EQ(mt_outcome(c->status), MtOutcome::kQueued);
  c = parse_mt_confirmation(confirmation({0x00, 0x00, 0x00, 0x00, 0xff, 0xfe}), &error);
  ASSERT_TRUE(c) << error;
  EXPECT_EQ(c->status, -2);  // signed
  EXPECT_EQ(mt_status_text(c->status), "-2 (IMEI not provisioned)");
}

TEST(DirectIpMtTest, RefusesAConfirmationOfTheWrongLength) {
  std::string error;
  std::string c = confirmation({0x00, 0x0f, 0x12, 0x06, 0x00, 0x01});
  c[2] = 0x1b;
  c[5] = 0x18;
  c.pop_back();
  EXPECT_FALSE(parse_mt_confirmation(c, &error));
  EXPECT_EQ(error, "MT confirmation IE 0x44 has 24 bytes, not 25");
  EXPECT_FALSE(parse_mt_confirmation(bytes({0x01, 0x00, 0x00}), &error));
  EXPECT_EQ(error, "no MT confirmation IE (0x44)");
}

TEST(DirectIpMtTest, StatusTableGivesEachOutcome) {
  EXPECT_EQ(mt_outcome(0), MtOutcome::kQueued);
  EXPECT_EQ(mt_outcome(50), MtOutcome::kQueued);
  EXPECT_EQ(mt_outcome(-5), MtOutcome::kRetryLater);
  EXPECT_EQ(mt_outcome(-6), MtOutcome::kRetryLater);
  for (int16_t refused : {-1, -2, -3, -4, -7, -8, -9, -10, -11, -12, -40}) {
    EXPECT_EQ(mt_outcome(refused), MtOutcome::kRefused) << refused;
  }
  EXPECT_EQ(mt_status_text(3), "3 (queued, position 3)");
  EXPECT_EQ(mt_status_text(-5), "-5 (MT queue full)");
  EXPECT_EQ(mt_status_text(-12), "-12 (client certificate rejected)");
  EXPECT_EQ(mt_status_text(-13), "-13 (unknown refusal)");
}

}  // namespace
}  // namespace acomms::drivers::directip
