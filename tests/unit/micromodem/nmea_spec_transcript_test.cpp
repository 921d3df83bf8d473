// The spec's real lines (§2.1) and sequence transcripts (§8), replayed
// verbatim: every line parses, every line this library has a type for
// parses as that type, and every host line is re-serialised byte for byte
// (what the driver writes is what the spec says a modem accepts).

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <string>

#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/line_framer.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"
#include "spec_lines.h"

namespace acomms::micromodem {
namespace {

// Parses `sentence` with its typed parser, if there is one, and returns the
// typed value written back as a Sentence (nullopt: no typed parser).
std::optional<Result<Sentence>> typed_round_trip(const Sentence& sentence) {
  auto via = [](auto result, auto write) -> Result<Sentence> {
    if (!result.ok()) return result.error();
    return write(*result);
  };
  Talker talker = sentence.talker == "CC" ? Talker::kHost : Talker::kModem;
  const std::string address = sentence.address();
  const std::string type = sentence.type;
  if (type == "CFG") return via(parse_config_parameter(sentence), [&](auto v) { return to_sentence(v, talker); });
  if (address == "CCCFQ") return via(parse_config_query(sentence), [](auto v) { return to_sentence(v); });
  if (type == "CLK") return via(parse_clock_time(sentence), [&](auto v) { return to_sentence(v, talker); });
  if (address == "CAREV") return via(parse_revision(sentence), [](auto v) { return to_sentence(v); });
  if (type == "CYC") return via(parse_cycle(sentence), [&](auto v) { return to_sentence(v, talker); });
  if (address == "CADRQ") return via(parse_data_request(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CCTXD") return via(parse_transmit_data(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CATXD") return via(parse_transmit_data_accepted(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CATXP") return via(parse_transmit_started(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CATXF") return via(parse_transmit_finished(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CARXP") return via(parse_receive_started(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CARXD") return via(parse_received_data(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CAACK") return via(parse_acknowledgement(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CAMSG") return via(parse_transaction_message(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CAERR") return via(parse_modem_error(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CACST") return via(parse_receive_statistics(sentence), [](auto v) { return to_sentence(v); });
  if (address == "CAXST") return via(parse_transmit_statistics(sentence), [](auto v) { return to_sentence(v); });
  return std::nullopt;
}

void replay(const std::vector<std::string_view>& lines, ChecksumRule rule, int expected_typed) {
  int typed = 0;
  for (std::string_view text : lines) {
    SCOPED_TRACE(std::string(text));
    Result<Sentence> sentence = parse_sentence(text, rule);
    ASSERT_TRUE(sentence.ok()) << sentence.error().text;
    std::optional<Result<Sentence>> rewritten = typed_round_trip(*sentence);
    if (rewritten) {
      ++typed;
      ASSERT_TRUE(rewritten->ok()) << rewritten->error().text;
    }
    if (sentence->talker != "CC") continue;
    // Host lines: the generic and the typed writer reproduce the spec's line.
    std::string expected(text);
    if (sentence->checksum == ChecksumState::kAbsent) {
      expected += "*";  // the spec omitted it: compare up to it
      EXPECT_EQ(serialize(*sentence).substr(0, expected.size()), expected);
    } else {
      EXPECT_EQ(serialize(*sentence), expected);
      if (rewritten) {
        EXPECT_EQ(serialize(rewritten->value()), expected);
      }
    }
  }
  EXPECT_EQ(typed, expected_typed);
}

TEST(NmeaSpecTranscriptTest, RealLinesFromSection2ParseAndMatchTheirTypes) {
  replay(spec::kRealLines, ChecksumRule::kRequired, 9);
}

TEST(NmeaSpecTranscriptTest, RealStatisticsLinesReadAsTheSpecDescribesThem) {
  Result<ReceiveStatistics> v8 = parse_receive_statistics(*parse_sentence(spec::kRealLines[7]));
  ASSERT_TRUE(v8.ok()) << v8.error().text;
  EXPECT_EQ(v8->version, 8);
  EXPECT_EQ(v8->field_count, 34u);
  EXPECT_EQ(v8->time_of_arrival, "20250606230123.348554");
  EXPECT_EQ(v8->spl, 123);
  EXPECT_EQ(v8->packet_type, kPacketFdp);
  EXPECT_DOUBLE_EQ(v8->snr_in, 26.0);
  EXPECT_DOUBLE_EQ(v8->mse, -6.48);
  EXPECT_EQ(v8->carrier, 25000);
  EXPECT_EQ(v8->bad_data_frames, 0);
  Result<ReceiveStatistics> v0 = parse_receive_statistics(*parse_sentence(spec::kRealLines[8]));
  ASSERT_TRUE(v0.ok()) << v0.error().text;
  EXPECT_EQ(v0->version, 0);
  EXPECT_EQ(v0->mode, 1);
  EXPECT_EQ(v0->time_of_arrival, "153026.0000");
  EXPECT_EQ(v0->source, 4);
  EXPECT_EQ(v0->bad_frames, 1);
  Result<TransmitStatistics> xst = parse_transmit_statistics(*parse_sentence(spec::kRealLines[6]));
  ASSERT_TRUE(xst.ok()) << xst.error().text;
  EXPECT_EQ(xst->version, 7);
  EXPECT_EQ(xst->mode, 0);
  EXPECT_EQ(xst->packet_type, kPacketFdp);
  EXPECT_EQ(xst->bytes, 2);
  EXPECT_EQ(xst->carrier_used, 25000);
  EXPECT_EQ(modem_generation(parse_revision(*parse_sentence(spec::kRealLines[3]))->revision).value(),
            ModemGeneration::kMM1);
}

TEST(NmeaSpecTranscriptTest, UnicastRate0TranscriptReplays) {
  replay(spec::kUnicastRate0, ChecksumRule::kRequired, 17);
}

TEST(NmeaSpecTranscriptTest, ThirdPartyTranscriptReplays) {
  replay(spec::kThirdParty, ChecksumRule::kRequired, 12);
}

TEST(NmeaSpecTranscriptTest, BroadcastTranscriptWithoutChecksumsParsesAsHostInput) {
  replay(spec::kBroadcastWithoutChecksums, ChecksumRule::kOptional, 6);
  EXPECT_EQ(serialize(to_sentence(TransmitData{2, 0, false, "\xCA\xFE"})).substr(0, 18),
            "$CCTXD,2,0,0,CAFE*");
}

TEST(NmeaSpecTranscriptTest, PingAndLblLinesParseAsSentences) {
  replay(spec::kPingAndLbl, ChecksumRule::kRequired, 2);  // the two CFG lines
}

TEST(NmeaSpecTranscriptTest, TheWholeTranscriptAsOneStreamFramesIntoTheSameLines) {
  std::string stream;
  for (std::string_view text : spec::kUnicastRate0) stream += std::string(text) + "\r\n";
  LineFramer framer;
  std::vector<std::string> lines;
  for (size_t at = 0; at < stream.size(); at += 7) {
    for (std::string& line : framer.push(std::string_view(stream).substr(at, 7))) lines.push_back(line);
  }
  ASSERT_EQ(lines.size(), spec::kUnicastRate0.size());
  for (size_t i = 0; i < lines.size(); ++i) EXPECT_EQ(lines[i], spec::kUnicastRate0[i]);
}

}  // namespace
}  // namespace acomms::micromodem
