// The extras' sentences (spec §6-§7) against the spec's own lines (§8.4,
// §8.5, §6: checksums as printed there): what the driver writes is byte for
// byte the transcript's host line, and the modem's lines parse to the
// values they carry. Bad fields are refused naming the field and bound.

#include <gtest/gtest.h>

#include "micromodem/nmea/fdp_sentences.h"
#include "micromodem/nmea/mini_packet_sentences.h"
#include "micromodem/nmea/ranging_sentences.h"

namespace acomms::micromodem {
namespace {

Sentence line(const char* text) {
  Result<Sentence> s = parse_sentence(text);
  EXPECT_TRUE(s.ok()) << text << ": " << (s ? "" : s.error().text);
  return s ? *s : Sentence{};
}

TEST(NmeaExtraSentences, PingTranscriptOfSection84) {
  EXPECT_EQ(serialize(to_sentence(Ping{1, 2}, Talker::kHost)), "$CCMPC,1,2*5D");
  Result<Ping> echo = parse_ping(line("$CAMPC,1,2*5F"));
  ASSERT_TRUE(echo.ok());
  EXPECT_EQ(*echo, (Ping{1, 2}));
  Result<Ping> heard = parse_ping(line("$CAMPA,1,2*5D"));
  ASSERT_TRUE(heard.ok());
  Result<PingReply> reply = parse_ping_reply(line("$CAMPR,2,1,1.0000*7D"));
  ASSERT_TRUE(reply.ok());
  EXPECT_EQ(reply->source, 2);  // the modem that replied
  EXPECT_EQ(reply->destination, 1);
  EXPECT_DOUBLE_EQ(reply->travel_time_s, 1.0);
}

TEST(NmeaExtraSentences, LblTranscriptsOfSection85) {
  NarrowbandInterrogation pnt;
  pnt.reply_frequency_hz = {26000, 27000, 0, 0};
  EXPECT_EQ(serialize(to_sentence(pnt)), "$CCPNT,25000,5,5,4000,26000,27000,0,0,1*65");
  RemusInterrogation pdt;
  pdt.channel = 2;
  pdt.listen = {true, true, false, false};
  EXPECT_EQ(serialize(to_sentence(pdt)), "$CCPDT,1,2,0,0,4000,1,1,0,0*6B");

  Result<TravelTimes> nb = parse_travel_times(line("$SNTTA,0.5007,0.9930,,,120301.25*59"));
  ASSERT_TRUE(nb.ok());
  EXPECT_DOUBLE_EQ(*nb->travel_time_s[0], 0.5007);
  EXPECT_DOUBLE_EQ(*nb->travel_time_s[1], 0.9930);
  EXPECT_FALSE(nb->travel_time_s[2].has_value());  // an empty field: no reply
  EXPECT_FALSE(nb->travel_time_s[3].has_value());
  EXPECT_EQ(nb->time, "120301.25");
  Result<TravelTimes> remus = parse_travel_times(line("$SNTTA,0.3335,0.6683,,,120311.00*53"));
  ASSERT_TRUE(remus.ok());
  EXPECT_DOUBLE_EQ(*remus->travel_time_s[1], 0.6683);
}

TEST(NmeaExtraSentences, TravelTimesOutsideTheirBoundAreRefusedNamingTheField) {
  Result<TravelTimes> negative = parse_travel_times(line(serialize({"SN", "TTA", {"-0.5", "", "", "", "1"}}).c_str()));
  ASSERT_FALSE(negative.ok());
  EXPECT_NE(negative.error().text.find("TA"), std::string::npos) << negative.error().text;
  EXPECT_FALSE(parse_ping_reply(line(serialize({"CA", "MPR", {"2", "1", "nan"}}).c_str())).ok());
}

TEST(NmeaExtraSentences, MiniPacketIsFourHexDigitsOf13Bits) {
  std::string muc = serialize(to_sentence(MiniPacket{1, 2, 0x1ABC}, Talker::kHost));
  EXPECT_TRUE(muc.starts_with("$CCMUC,1,2,1ABC*")) << muc;
  Result<MiniPacket> lower = parse_mini_packet(line(serialize({"CA", "MUA", {"2", "0", "1fff"}}).c_str()));
  ASSERT_TRUE(lower.ok());
  EXPECT_EQ(lower->value, 0x1FFFu);
  Result<MiniPacket> wide = parse_mini_packet(line(serialize({"CA", "MUA", {"2", "0", "2000"}}).c_str()));
  ASSERT_FALSE(wide.ok());
  EXPECT_NE(wide.error().text.find("0000..1FFF"), std::string::npos) << wide.error().text;
  EXPECT_FALSE(parse_mini_packet(line(serialize({"CA", "MUA", {"2", "0", "1AB"}}).c_str())).ok());
}

TEST(NmeaExtraSentences, FdpCommandOfTheCourseNotesAndReceivedFrames) {
  FdpTransmit tdp{2, 1, false, std::string("\xDE\xAD\xBE\xEF", 4)};
  std::string tdp_line = serialize(to_sentence(tdp));
  EXPECT_TRUE(tdp_line.starts_with("$CCTDP,2,1,0,0,DEADBEEF*")) << tdp_line;  // G-COURSE's example
  Result<FdpReceived> rdp =
      parse_fdp_received(line(serialize({"CA", "RDP", {"1", "2", "5", "0", "0", "1;2;fd00", "1;4;deadbeef"}}).c_str()));
  ASSERT_TRUE(rdp.ok()) << rdp.error().text;
  EXPECT_TRUE(rdp->intact());
  EXPECT_EQ(rdp->payload(), std::string("\xFD\x00\xDE\xAD\xBE\xEF", 6));
  Result<FdpReceived> damaged =
      parse_fdp_received(line(serialize({"CA", "RDP", {"1", "2", "5", "0", "0", "0;2;fd00", ""}}).c_str()));
  ASSERT_TRUE(damaged.ok());
  EXPECT_FALSE(damaged->intact());
  Result<FdpReceived> lying =
      parse_fdp_received(line(serialize({"CA", "RDP", {"1", "2", "5", "0", "0", "1;3;fd00", ""}}).c_str()));
  ASSERT_FALSE(lying.ok());
  EXPECT_NE(lying.error().text.find("says 3 bytes but carries 2"), std::string::npos) << lying.error().text;
  EXPECT_EQ(fdp_max_data_bytes(1), 192);
  EXPECT_EQ(fdp_max_data_bytes(3), 512);
  EXPECT_EQ(fdp_max_data_bytes(5), 2048);
  EXPECT_EQ(fdp_max_data_bytes(2), 0);
}

}  // namespace
}  // namespace acomms::micromodem
