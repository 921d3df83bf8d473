// The typed sentences: every one survives to_sentence → serialize → parse
// → parse_*, and each parser refuses what its sentence cannot hold, naming
// the field.

#include <gtest/gtest.h>

#include <string>

#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/hex.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"

namespace acomms::micromodem {
namespace {

// to_sentence → line → Sentence → T.
template <typename T, typename Parse>
T round_trip(const Sentence& sentence, Parse parse) {
  std::string line = serialize(sentence);
  Result<Sentence> parsed = parse_sentence(line);
  EXPECT_TRUE(parsed.ok()) << line << ": " << parsed.error().text;
  if (!parsed.ok()) return T{};
  Result<T> typed = parse(*parsed);
  EXPECT_TRUE(typed.ok()) << line << ": " << typed.error().text;
  return typed.ok() ? *typed : T{};
}

Sentence line(std::string_view text) {
  Result<Sentence> parsed = parse_sentence(text, ChecksumRule::kOptional);
  EXPECT_TRUE(parsed.ok()) << text;
  return parsed.ok() ? *parsed : Sentence{};
}

TEST(NmeaTypedSentencesTest, ConfigParameterRoundTripsInBothDirections) {
  ConfigParameter src{"SRC", "1"};
  EXPECT_EQ(serialize(to_sentence(src, Talker::kModem)), "$CACFG,SRC,1*33");
  EXPECT_EQ(round_trip<ConfigParameter>(to_sentence(src, Talker::kHost), parse_config_parameter), src);
  ConfigParameter dotted{"psk.packet.mod_hdr_version", "0"};
  EXPECT_EQ(round_trip<ConfigParameter>(to_sentence(dotted, Talker::kModem), parse_config_parameter),
            dotted);
  ConfigParameter group{"psk", ""};  // an MM2 group header in a dump
  EXPECT_EQ(parse_config_parameter(line("$CACFG,psk")).value(), group);
}

TEST(NmeaTypedSentencesTest, ConfigQueryRoundTrips) {
  EXPECT_EQ(round_trip<ConfigQuery>(to_sentence(ConfigQuery{"ALL"}), parse_config_query).name, "ALL");
  EXPECT_EQ(parse_config_query(line("$CCCFQ,")).error().kind, ErrorKind::kBadField);
}

TEST(NmeaTypedSentencesTest, ClockTimeRoundTripsWithTwoDigitFields) {
  ClockTime time{2026, 3, 7, 9, 5, 0};
  EXPECT_EQ(serialize(to_sentence(time, Talker::kHost)).substr(0, 26), "$CCCLK,2026,03,07,09,05,00");
  EXPECT_EQ(round_trip<ClockTime>(to_sentence(time, Talker::kModem), parse_clock_time), time);
  Result<ClockTime> bad = parse_clock_time(line("$CACLK,2026,13,07,09,05,00"));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().text, "CACLK field 2 (month) 13 is outside 1..12");
}

TEST(NmeaTypedSentencesTest, RevisionRoundTripsAndTellsMm1FromMm2) {
  Revision mm2{"181807", "AUV", "2.0.27087"};
  EXPECT_EQ(serialize(to_sentence(mm2)), "$CAREV,181807,AUV,2.0.27087*12");
  EXPECT_EQ(round_trip<Revision>(to_sentence(mm2), parse_revision), mm2);
  EXPECT_EQ(modem_generation("2.0.27087").value(), ModemGeneration::kMM2);
  EXPECT_EQ(modem_generation("0.93.0.09").value(), ModemGeneration::kMM1);
  EXPECT_EQ(revision_numbers("0.93.0.09").value(), (std::vector<int>{0, 93, 0, 9}));
  EXPECT_FALSE(modem_generation("1.0.0").ok());
  EXPECT_FALSE(modem_generation("2..1").ok());
  EXPECT_FALSE(modem_generation("").ok());
  EXPECT_FALSE(modem_generation("v2.0").ok());
  EXPECT_TRUE(parse_revision(line("$CAREV,000001,INIT,2.0.27087"))->is_boot());
}

TEST(NmeaTypedSentencesTest, CycleRoundTripsAndChecksItsBounds) {
  Cycle cycle{0, 1, 2, 5, true, 8};
  EXPECT_EQ(round_trip<Cycle>(to_sentence(cycle, Talker::kHost), parse_cycle), cycle);
  EXPECT_EQ(round_trip<Cycle>(to_sentence(cycle, Talker::kModem), parse_cycle), cycle);
  EXPECT_EQ(parse_cycle(line("$CCCYC,0,1,2,7,1,1")).error().text,
            "CCCYC field 4 (Packet Type) 7 is outside 0..6");
  EXPECT_EQ(parse_cycle(line("$CCCYC,0,128,2,1,1,1")).error().kind, ErrorKind::kBadField);
  EXPECT_EQ(parse_cycle(line("$CCCYC,0,1,2,1,1")).error().kind, ErrorKind::kMissingField);
  EXPECT_EQ(parse_cycle(line("$CCCYC,0,1,x,1,1,1")).error().text,
            "CCCYC field 3 (ADR2) 'x' is not an integer");
  EXPECT_EQ(parse_cycle(line("$CATXF,2")).error().kind, ErrorKind::kWrongSentence);
}

TEST(NmeaTypedSentencesTest, DataRequestRoundTrips) {
  DataRequest request{"120001", 1, 2, true, 32, 1};
  EXPECT_EQ(serialize(to_sentence(request)), "$CADRQ,120001,1,2,1,32,1*45");
  EXPECT_EQ(round_trip<DataRequest>(to_sentence(request), parse_data_request), request);
  EXPECT_EQ(parse_data_request(line("$CADRQ,120001,1,2,1,32,0")).error().kind, ErrorKind::kBadField);
}

TEST(NmeaTypedSentencesTest, TransmitDataCarriesBytesAsUpperCaseHex) {
  TransmitData frame{1, 2, true, "Hello"};
  EXPECT_EQ(serialize(to_sentence(frame)), "$CCTXD,1,2,1,48656C6C6F*05");
  EXPECT_EQ(round_trip<TransmitData>(to_sentence(frame), parse_transmit_data), frame);
  TransmitData binary{3, 0, false, std::string("\x00\xff\x10", 3)};
  EXPECT_EQ(round_trip<TransmitData>(to_sentence(binary), parse_transmit_data), binary);
  TransmitData empty{2, 1, true, ""};
  EXPECT_EQ(serialize(to_sentence(empty)), "$CCTXD,2,1,1,*7A");
  EXPECT_EQ(parse_transmit_data(line("$CCTXD,2,1,1,ABC")).error().kind, ErrorKind::kBadField);
}

TEST(NmeaTypedSentencesTest, TransmitDataAcceptedRoundTrips) {
  TransmitDataAccepted accepted{1, 2, true, 5};
  EXPECT_EQ(serialize(to_sentence(accepted)), "$CATXD,1,2,1,5*4D");
  EXPECT_EQ(round_trip<TransmitDataAccepted>(to_sentence(accepted), parse_transmit_data_accepted),
            accepted);
}

TEST(NmeaTypedSentencesTest, TransmitAndReceiveProgressRoundTrip) {
  EXPECT_EQ(serialize(to_sentence(TransmitStarted{2})), "$CATXP,2*40");
  EXPECT_EQ(serialize(to_sentence(TransmitFinished{28})), "$CATXF,28*6E");
  EXPECT_EQ(round_trip<TransmitStarted>(to_sentence(TransmitStarted{64}), parse_transmit_started).bytes, 64);
  EXPECT_EQ(round_trip<TransmitFinished>(to_sentence(TransmitFinished{5}), parse_transmit_finished).bytes, 5);
  EXPECT_EQ(serialize(to_sentence(ReceiveStarted{0})), "$CARXP,0*44");
  EXPECT_EQ(round_trip<ReceiveStarted>(to_sentence(ReceiveStarted{1}), parse_receive_started).type, 1);
  EXPECT_FALSE(parse_receive_started(line("$CARXP,2")).ok());
}

TEST(NmeaTypedSentencesTest, ReceivedDataDecodesEitherHexCase) {
  ReceivedData frame{1, 2, true, 1, "Hello"};
  EXPECT_EQ(serialize(to_sentence(frame)), "$CARXD,1,2,1,1,48656C6C6F*1C");
  EXPECT_EQ(round_trip<ReceivedData>(to_sentence(frame), parse_received_data), frame);
  EXPECT_EQ(parse_received_data(line("$CARXD,1,2,1,1,0801000700ff"))->data,
            std::string("\x08\x01\x00\x07\x00\xff", 6));
  EXPECT_EQ(parse_received_data(line("$CARXD,2,1,1,2,"))->data, "");
}

TEST(NmeaTypedSentencesTest, AcknowledgementRoundTripsAndNeedsOnlyThreeFields) {
  Acknowledgement ack{2, 1, 1};
  EXPECT_EQ(serialize(to_sentence(ack)), "$CAACK,2,1,1,1*48");
  EXPECT_EQ(round_trip<Acknowledgement>(to_sentence(ack), parse_acknowledgement), ack);
  EXPECT_EQ(parse_acknowledgement(line("$CAACK,2,1,3")).value(), (Acknowledgement{2, 1, 3}));
}

TEST(NmeaTypedSentencesTest, TransactionMessageKnowsBothSpellingsOfBadCrc) {
  TransactionMessage message{"BAD_CRC", "1"};
  EXPECT_EQ(round_trip<TransactionMessage>(to_sentence(message), parse_transaction_message), message);
  EXPECT_TRUE(parse_transaction_message(line("$CAMSG,Bad CRC,1"))->is_bad_crc());
  EXPECT_TRUE(parse_transaction_message(line("$CAMSG,PACKET_TIMEOUT,0"))->is_packet_timeout());
}

TEST(NmeaTypedSentencesTest, ModemErrorKeepsCommasInItsMessage) {
  ModemError error{"120102", "DATA_TIMEOUT", "1", "no data, sending what I have"};
  EXPECT_EQ(parse_modem_error(line("$CAERR,120102,DATA_TIMEOUT,1,no data, sending what I have"))
                .value(),
            error);
  ModemError simple{"120102", "NMEA", "3", "Bad checksum"};
  EXPECT_EQ(round_trip<ModemError>(to_sentence(simple), parse_modem_error), simple);
}

ReceiveStatistics sample_statistics(int version) {
  ReceiveStatistics s;
  s.version = version;
  s.mode = 1;
  s.time_of_arrival = "20260102030405.123456";
  s.clock_status = 3;
  s.mf_peak = 32767;
  s.mf_power = 45;
  s.mf_ratio = 102;
  s.spl = 123;
  s.analog_gain = 7;
  s.shift_previous = 1, s.shift_current = 2, s.shift_detect = 3, s.shift_baseband = 4;
  s.rate = 5, s.source = 1, s.destination = 2, s.psk_error = 3, s.packet_type = kPacketPsk;
  s.frames = 8, s.bad_frames = 2;
  s.rss = 150, s.snr_in = 26.5, s.snr_out = 9.48, s.snr_symbol = -100, s.mse = -6.48;
  s.dqf = 200, s.doppler = -0.01, s.noise = 51, s.carrier = 25000, s.bandwidth = 5000;
  if (version >= 7) s.sequence = 12, s.data_rate = 5, s.data_frames = 3, s.bad_data_frames = 0;
  return s;
}

TEST(NmeaTypedSentencesTest, ReceiveStatisticsRoundTripInEveryLayout) {
  for (int version : {0, 6, 7, 8}) {
    ReceiveStatistics s = sample_statistics(version);
    Sentence sentence = to_sentence(s);
    EXPECT_EQ(sentence.fields.size(), version == 0 ? 29u : version == 6 ? 30u : 34u);
    EXPECT_EQ(round_trip<ReceiveStatistics>(sentence, parse_receive_statistics), s)
        << "version " << version;
  }
}

TEST(NmeaTypedSentencesTest, ReceiveStatisticsToleratesAShortLineButNotAWrongField) {
  Result<ReceiveStatistics> timeout = parse_receive_statistics(line("$CACST,6,2"));
  ASSERT_TRUE(timeout.ok());
  EXPECT_EQ(timeout->mode, 2);
  EXPECT_EQ(timeout->field_count, 2u);
  EXPECT_EQ(timeout->packet_type, kPacketUnknown);
  EXPECT_EQ(parse_receive_statistics(line("$CACST,6,0,t,0,x")).error().text,
            "CACST field 5 (matched-filter peak) 'x' is not an integer");
  EXPECT_EQ(parse_receive_statistics(line("$CACST")).error().kind, ErrorKind::kMissingField);
}

TEST(NmeaTypedSentencesTest, TransmitStatisticsRoundTripInEveryLayout) {
  for (int version : {0, 6, 7}) {
    TransmitStatistics s{version, "20260102", "030405.000935", 3, 0, 200, 5000, 25000, 1, 1, 2,
                         true, 3, 3, kPacketPsk, 192, version >= 7 ? 25000 : 0};
    Sentence sentence = to_sentence(s);
    EXPECT_EQ(sentence.fields.size(), version == 0 ? 15u : version == 6 ? 16u : 17u);
    EXPECT_EQ(round_trip<TransmitStatistics>(sentence, parse_transmit_statistics), s)
        << "version " << version;
  }
}

TEST(NmeaHexTest, EncodesUpperCaseAndRefusesOddOrNonHexInput) {
  EXPECT_EQ(hex_encode(std::string("\x00\xab\xff", 3)), "00ABFF");
  EXPECT_EQ(hex_decode("00abFF").value(), std::string("\x00\xab\xff", 3));
  EXPECT_EQ(hex_decode("").value(), "");
  EXPECT_EQ(hex_decode("ABC").error().kind, ErrorKind::kBadField);
  EXPECT_EQ(hex_decode("0G").error().kind, ErrorKind::kBadField);
}

}  // namespace
}  // namespace acomms::micromodem
