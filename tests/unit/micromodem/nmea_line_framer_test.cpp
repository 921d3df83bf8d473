// LineFramer: spec §2.3 rules 1-4 on a byte stream cut into any chunks.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "micromodem/nmea/line_framer.h"

namespace acomms::micromodem {
namespace {

using Lines = std::vector<std::string>;

TEST(LineFramerTest, YieldsEachLineWithoutItsLineEnd) {
  LineFramer framer;
  EXPECT_EQ(framer.push("$CATXF,2*56\r\n$CARXP,0*44\r\n"), (Lines{"$CATXF,2*56", "$CARXP,0*44"}));
  EXPECT_EQ(framer.counters().lines, 2u);
  EXPECT_EQ(framer.buffered(), 0u);
}

TEST(LineFramerTest, AcceptsCrOrLfAloneAndIgnoresEmptyLines) {
  LineFramer framer;
  EXPECT_EQ(framer.push("$A*00\r\r\n\n$B*00\n$C*00\r"), (Lines{"$A*00", "$B*00", "$C*00"}));
  EXPECT_EQ(framer.counters().noise_bytes, 0u);
}

TEST(LineFramerTest, AnySplitOfTheStreamGivesTheSameLines) {
  const std::string stream = "junk$CACYC,0,1,2,0,1,1*58\r\n$CADRQ,120001,1,2,1,32,1*45\r\n";
  Lines whole = LineFramer().push(stream);
  ASSERT_EQ(whole, (Lines{"$CACYC,0,1,2,0,1,1*58", "$CADRQ,120001,1,2,1,32,1*45"}));
  for (size_t chunk = 1; chunk <= stream.size(); ++chunk) {
    LineFramer framer;
    Lines lines;
    for (size_t at = 0; at < stream.size(); at += chunk) {
      for (std::string& line : framer.push(stream.substr(at, chunk))) lines.push_back(line);
    }
    EXPECT_EQ(lines, whole) << "chunks of " << chunk;
    EXPECT_EQ(framer.counters().noise_bytes, 4u);
  }
}

TEST(LineFramerTest, DiscardsAndCountsBytesBeforeTheFirstDollar) {
  LineFramer framer;
  EXPECT_EQ(framer.push(std::string("\x00\xff\x13garbage,*12\r\n$CATXF,2*56\r\n", 29)),
            (Lines{"$CATXF,2*56"}));
  EXPECT_EQ(framer.counters().noise_bytes, 14u);
}

TEST(LineFramerTest, ASecondDollarDropsTheTruncatedLineAndStartsAgain) {
  LineFramer framer;
  EXPECT_EQ(framer.push("$CARXD,1,2,1,1,4865$CATXF,2*56\r\n"), (Lines{"$CATXF,2*56"}));
  EXPECT_EQ(framer.counters().truncated_lines, 1u);
}

TEST(LineFramerTest, AnOverLongLineIsDroppedToItsEndAndCounted) {
  LineFramer framer(32);
  std::string longer(100, 'A');
  EXPECT_TRUE(framer.push("$CARXD," + longer).empty());
  EXPECT_LE(framer.buffered(), 32u) << "the buffer stays bounded";
  EXPECT_TRUE(framer.push(longer + "\r\n").empty()) << "the rest of it is dropped too";
  EXPECT_EQ(framer.push("$CATXF,2*56\r\n"), (Lines{"$CATXF,2*56"}));
  EXPECT_EQ(framer.counters().overlong_lines, 1u);
  EXPECT_EQ(framer.counters().lines, 1u);
}

TEST(LineFramerTest, ALineOfExactlyTheBoundIsKept) {
  LineFramer framer(8);
  EXPECT_EQ(framer.push("$2345678\r\n"), (Lines{"$2345678"}));
  EXPECT_EQ(framer.push("$23456789\r\n"), Lines{});
  EXPECT_EQ(framer.counters().overlong_lines, 1u);
}

TEST(LineFramerTest, ADollarEndsTheDiscardingOfAnOverLongLine) {
  LineFramer framer(16);
  EXPECT_EQ(framer.push(std::string(40, '\x7f') + "$" + std::string(40, 'x') + "$CATXF,2*56\n"),
            (Lines{"$CATXF,2*56"}));
  EXPECT_EQ(framer.counters().overlong_lines, 1u);
}

TEST(LineFramerTest, ResetForgetsAPartialLine) {
  LineFramer framer;
  EXPECT_TRUE(framer.push("$CARXD,1,2").empty());
  framer.reset();
  EXPECT_EQ(framer.push(",1,1,48*00\r\n$CATXF,2*56\r\n"), (Lines{"$CATXF,2*56"}));
}

}  // namespace
}  // namespace acomms::micromodem
