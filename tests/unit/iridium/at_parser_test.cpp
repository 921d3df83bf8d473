// The Iridium AT library against the spec's own bytes: checksum vectors
// (§4.1), the +SBDWB blocks and +SBDRB replies of the §8 transcript, line
// classification with and without spaces (§2), both +SBDIXA prefixes (§5.1),
// and a reader that survives echo, unsolicited lines before a block,
// garbage, over-long lines and any chunking.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "iridium/at/at_line.h"
#include "iridium/at/at_reader.h"
#include "iridium/at/sbd_binary.h"

namespace acomms::iridium {
namespace {

using Kind = AtLine::Kind;

std::string bytes(std::initializer_list<int> list) {
  std::string out;
  for (int b : list) out.push_back(static_cast<char>(b));
  return out;
}

std::vector<AtEvent> read_all(std::string_view stream, size_t chunk = 0, bool binary = false) {
  AtReader reader;
  if (binary) reader.expect_binary();
  if (chunk == 0) return reader.push(stream);
  std::vector<AtEvent> out;
  for (size_t at = 0; at < stream.size(); at += chunk) {
    for (auto& e : reader.push(stream.substr(at, chunk))) out.push_back(std::move(e));
  }
  return out;
}

TEST(SbdChecksumTest, MatchesTheSpecsVectors) {
  EXPECT_EQ(sbd_checksum("hello"), 0x0214);
  EXPECT_EQ(sbd_checksum(bytes({0xff, 0xff, 0xff})), 0x02fd);
  EXPECT_EQ(sbd_checksum(std::string(340, '\xff')), 0x52ac);  // 0x152AC truncated
  EXPECT_EQ(sbd_checksum(""), 0);
}

TEST(SbdwbWriterTest, WritesTheTranscriptsBlocksByteForByte) {
  EXPECT_EQ(sbdwb_command(12), "AT+SBDWB=12\r");
  EXPECT_EQ(sbdwb_block("acommsd-test"), "acommsd-test" + bytes({0x04, 0xd1}));
  EXPECT_EQ(sbdwb_block("go home!"), bytes({0x67, 0x6f, 0x20, 0x68, 0x6f, 0x6d, 0x65, 0x21, 0x02, 0xc0}));
  EXPECT_EQ(sbdwb_block("hello"), "hello" + bytes({0x02, 0x14}));
}

TEST(AtLineTest, ClassifiesFinalCodesDigitsAndReady) {
  EXPECT_EQ(classify_line("OK").kind, Kind::kOk);
  EXPECT_EQ(classify_line("ERROR").kind, Kind::kError);
  EXPECT_EQ(classify_line("READY").kind, Kind::kReady);
  AtLine digit = classify_line("2");
  EXPECT_EQ(digit.kind, Kind::kDigit);
  EXPECT_EQ(digit.digit, 2);
  EXPECT_EQ(classify_line("300234010000001").kind, Kind::kText);  // an IMEI is text
  EXPECT_EQ(classify_line("SBDRING").kind, Kind::kRing);
  EXPECT_TRUE(classify_line("SBDRING").unsolicited());
}

TEST(AtLineTest, ParsesSbdixWithSpacesAndSignedFields) {
  AtLine line = classify_line("+SBDIX: 0, 41, 1, 17, 9, 0");
  ASSERT_EQ(line.kind, Kind::kSession);
  EXPECT_EQ(line.session.mo_status, 0);
  EXPECT_EQ(line.session.momsn, 41);
  EXPECT_EQ(line.session.mt_status, 1);
  EXPECT_EQ(line.session.mtmsn, 17);
  EXPECT_EQ(line.session.mt_length, 9);
  EXPECT_EQ(line.session.mt_queued, 0);
  EXPECT_FALSE(line.session.answered_alert);
  AtLine tight = classify_line("+SBDIX:32,42,0,-1,0,0");
  ASSERT_EQ(tight.kind, Kind::kSession);
  EXPECT_EQ(tight.session.mo_status, 32);
  EXPECT_EQ(tight.session.mtmsn, -1);
}

TEST(AtLineTest, AcceptsBothPrefixesOfTheAlertAnswer) {
  AtLine ixa = classify_line("+SBDIXA: 0, 43, 1, 18, 4, 1");
  ASSERT_EQ(ixa.kind, Kind::kSession);
  EXPECT_TRUE(ixa.session.answered_alert);
  EXPECT_EQ(ixa.session.mtmsn, 18);
  EXPECT_EQ(ixa.session.mt_queued, 1);
  EXPECT_EQ(classify_line("+SBDIX: 0, 43, 1, 18, 4, 1").session.mtmsn, 18);
}

TEST(AtLineTest, ParsesStatusSignalAndIndicators) {
  AtLine sx = classify_line("+SBDSX: 0, 41, 0, -1, 0, 0");
  ASSERT_EQ(sx.kind, Kind::kStatus);
  EXPECT_TRUE(sx.status.extended);
  EXPECT_EQ(sx.status.momsn, 41);
  EXPECT_EQ(sx.status.mtmsn, -1);
  AtLine s = classify_line("+SBDS: 1, 7, 1, 3");
  ASSERT_EQ(s.kind, Kind::kStatus);
  EXPECT_FALSE(s.status.extended);
  EXPECT_EQ(s.status.mo_flag, 1);
  EXPECT_EQ(s.status.mtmsn, 3);
  EXPECT_EQ(classify_line("+CSQ:5").rssi, 5);
  EXPECT_EQ(classify_line("+CSQ: 0").rssi, 0);
  EXPECT_EQ(classify_line("+CSQF:2").kind, Kind::kSignal);
  AtLine ciev = classify_line("+CIEV:1,0");
  ASSERT_EQ(ciev.kind, Kind::kIndicator);
  EXPECT_EQ(ciev.indicator.indicator, 1);
  EXPECT_EQ(ciev.indicator.value, 0);
  EXPECT_TRUE(ciev.unsolicited());
  EXPECT_TRUE(classify_line("+AREG:1,0").unsolicited());
}

TEST(AtLineTest, KnownPrefixesWithBadFieldsAreMalformedNotGuessed) {
  for (const char* bad : {"+SBDIX: 0, 41, 1", "+SBDIX: 0, 41, x, 17, 9, 0", "+SBDIX: 0,41,1,17,9,0,5", "+CSQ:9",
                          "+CSQ:", "+SBDSX: 0, 41", "+CIEV:1", "+SBDIX: 0, 41, , 17, 9, 0"}) {
    EXPECT_EQ(classify_line(bad).kind, Kind::kMalformed) << bad;
  }
}

// The modem's side of spec §8, first MO: bytes exactly as they arrive.
TEST(AtReaderTest, ReadsTheTranscriptsMtBlockAndTheOkAfterIt) {
  const std::string stream = "\r\n+SBDIX: 0, 41, 1, 17, 9, 0\r\n\r\nOK\r\n";
  auto events = read_all(stream);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].line.session.mt_length, 9);
  EXPECT_EQ(events[1].line.kind, Kind::kOk);

  const std::string block = bytes({0x00, 0x09, 0x70, 0x69, 0x6e, 0x67, 0x20, 0x30, 0x30, 0x30, 0x31, 0x02, 0x8f});
  for (size_t chunk : {0, 1, 2, 5}) {
    auto got = read_all(block + "\r\nOK\r\n", chunk, true);
    ASSERT_EQ(got.size(), 2u) << chunk;
    ASSERT_EQ(got[0].kind, AtEvent::Kind::kBlock);
    EXPECT_EQ(got[0].block.payload, "ping 0001");
    EXPECT_EQ(got[0].block.checksum, 0x028f);
    EXPECT_TRUE(got[0].block.checksum_ok);
    EXPECT_EQ(got[1].line.kind, Kind::kOk);
  }
  auto second = read_all(bytes({0x00, 0x04, 0x01, 0x02, 0x03, 0x04, 0x00, 0x0a}) + "\r\nOK\r\n", 0, true);
  EXPECT_EQ(second[0].block.payload, bytes({1, 2, 3, 4}));
  EXPECT_TRUE(second[0].block.checksum_ok);
  auto third = read_all(bytes({0x00, 0x02, 0xab, 0xcd, 0x01, 0x78}), 0, true);
  EXPECT_TRUE(third[0].block.checksum_ok);
  auto empty = read_all(bytes({0, 0, 0, 0}) + "\r\nOK\r\n", 0, true);
  ASSERT_EQ(empty[0].kind, AtEvent::Kind::kBlock);
  EXPECT_TRUE(empty[0].block.payload.empty());
  EXPECT_TRUE(empty[0].block.checksum_ok);
}

TEST(AtReaderTest, AWrongChecksumIsReportedAndCounted) {
  AtReader reader;
  reader.expect_binary();
  auto events = reader.push(bytes({0x00, 0x05}) + "hello" + bytes({0x02, 0x15}));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_FALSE(events[0].block.checksum_ok);
  EXPECT_EQ(reader.counters().bad_checksums, 1u);
}

TEST(AtReaderTest, UnsolicitedLinesAndEchoBeforeTheBlockAreLinesNotLength) {
  const std::string stream = "AT+SBDRB\r\r\nSBDRING\r\n+CIEV:0,4\r\n" +
                             bytes({0x00, 0x05}) + "hello" + bytes({0x02, 0x14}) + "\r\nOK\r\n";
  for (size_t chunk : {0, 1, 3}) {
    auto events = read_all(stream, chunk, true);
    ASSERT_EQ(events.size(), 5u) << chunk;
    EXPECT_EQ(events[0].line.text, "AT+SBDRB");
    EXPECT_EQ(events[1].line.kind, Kind::kRing);
    EXPECT_EQ(events[2].line.kind, Kind::kIndicator);
    ASSERT_EQ(events[3].kind, AtEvent::Kind::kBlock);
    EXPECT_EQ(events[3].block.payload, "hello");
    EXPECT_EQ(events[4].line.kind, Kind::kOk);
  }
}

TEST(AtReaderTest, ALengthOverTheMtLimitIsAbandonedAndLinesResume) {
  AtReader reader;
  reader.expect_binary();
  auto events = reader.push(bytes({0x01, 0x0f}) + "\r\nOK\r\n");
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, AtEvent::Kind::kBadBlock);
  EXPECT_EQ(events[0].bad_length, 271u);
  EXPECT_EQ(events[1].line.kind, Kind::kOk);
  EXPECT_FALSE(reader.expecting_binary());
  EXPECT_EQ(reader.counters().bad_lengths, 1u);
}

TEST(AtReaderTest, GarbageAndOverlongLinesAreDroppedAndCounted) {
  AtReader reader;
  std::string stream = bytes({0x00, 0xff, 0x13}) + "noise\r\n" + std::string(2000, 'x') + "\r\nOK\r\n\n\n\r";
  auto events = reader.push(stream);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].line.kind, Kind::kOk);
  EXPECT_EQ(reader.counters().garbled_lines, 1u);
  EXPECT_EQ(reader.counters().overlong_lines, 1u);
  EXPECT_LE(reader.buffered(), kMaxLineBytes);
}

TEST(AtReaderTest, EchoedCommandsComeAsTextLines) {
  // Echo on (factory profile): "AT<CR>" then "<CR><LF>OK<CR><LF>" (spec §8, first line).
  auto events = read_all("AT\r\r\nOK\r\nATE0\r\r\nOK\r\n");
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[0].line.text, "AT");
  EXPECT_EQ(events[1].line.kind, Kind::kOk);
  EXPECT_EQ(events[2].line.text, "ATE0");
  // Numeric mode: "0<CR>" is a digit line to the reader; the channel decides.
  auto numeric = read_all("0\r");
  ASSERT_EQ(numeric.size(), 1u);
  EXPECT_EQ(numeric[0].line.digit, 0);
}

}  // namespace
}  // namespace acomms::iridium
