// parse_sentence / serialize: the grammar of spec §2 and what a robust
// reader refuses (§2.3 rule 5), each refusal with its own kind.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {
namespace {

ErrorKind refusal(std::string_view line, ChecksumRule rule = ChecksumRule::kRequired) {
  Result<Sentence> parsed = parse_sentence(line, rule);
  EXPECT_FALSE(parsed.ok()) << line;
  if (parsed.ok()) return ErrorKind::kEmpty;
  EXPECT_FALSE(parsed.error().text.empty()) << "every refusal says why: " << line;
  return parsed.error().kind;
}

TEST(NmeaChecksumTest, IsTheXorOfTheBytesBetweenDollarAndStar) {
  EXPECT_EQ(nmea_checksum("CACFG,SRC,1"), 0x33);  // the spec's worked example
  EXPECT_EQ(nmea_checksum(""), 0x00);
  EXPECT_EQ(nmea_checksum("A"), 0x41);
  EXPECT_EQ(nmea_checksum("AA"), 0x00);
}

TEST(NmeaSentenceTest, ParsesTalkerTypeAndFields) {
  Result<Sentence> parsed = parse_sentence("$CACFG,SRC,1*33\r\n");
  ASSERT_TRUE(parsed.ok()) << parsed.error().text;
  EXPECT_EQ(parsed->talker, "CA");
  EXPECT_EQ(parsed->type, "CFG");
  EXPECT_EQ(parsed->address(), "CACFG");
  EXPECT_TRUE(parsed->is("CACFG"));
  EXPECT_EQ(parsed->fields, (std::vector<std::string>{"SRC", "1"}));
  EXPECT_EQ(parsed->field(1), "SRC");
  EXPECT_EQ(parsed->field(3), "");
  EXPECT_EQ(parsed->checksum, ChecksumState::kVerified);
}

TEST(NmeaSentenceTest, KeepsEmptyFieldsInPlace) {
  Result<Sentence> parsed = parse_sentence("$SNTTA,0.5007,0.9930,,,120301.25*59");
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed->fields, (std::vector<std::string>{"0.5007", "0.9930", "", "", "120301.25"}));
  Result<Sentence> trailing = parse_sentence("$CCTXD,2,1,1,*7A");
  ASSERT_TRUE(trailing.ok());
  EXPECT_EQ(trailing->fields.size(), 4u);
  EXPECT_EQ(trailing->field(4), "");
}

TEST(NmeaSentenceTest, AcceptsALowerCaseChecksum) {
  EXPECT_TRUE(parse_sentence("$CATXF,28*6e").ok());
}

TEST(NmeaSentenceTest, SerializesWithAnUpperCaseChecksumAndNoLineEnd) {
  Sentence sentence{"CA", "TXF", {"28"}};
  EXPECT_EQ(serialize(sentence), "$CATXF,28*6E");
  EXPECT_EQ(serialize(Sentence{"CC", "CYC", {}}), "$CCCYC*59");
}

TEST(NmeaSentenceTest, RefusesAWrongChecksumAndSaysWhichItShouldBe) {
  Result<Sentence> parsed = parse_sentence("$CACFG,SRC,1*34");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error().kind, ErrorKind::kBadChecksum);
  EXPECT_NE(parsed.error().text.find("should be 33"), std::string::npos) << parsed.error().text;
}

TEST(NmeaSentenceTest, ModemLinesWithoutAChecksumAreDamaged) {
  EXPECT_EQ(refusal("$CACFG,SRC,1"), ErrorKind::kMissingChecksum);
}

TEST(NmeaSentenceTest, HostLinesMayOmitTheChecksum) {
  Result<Sentence> parsed = parse_sentence("$CCCFG,SRC,1\r\n", ChecksumRule::kOptional);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed->checksum, ChecksumState::kAbsent);
  EXPECT_EQ(serialize(*parsed), "$CCCFG,SRC,1*31");
}

TEST(NmeaSentenceTest, AnEightDigitChecksumIsPresentButNotVerified) {
  Result<Sentence> parsed = parse_sentence("$CATXF,2*DEADBEEF");
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed->checksum, ChecksumState::kUnverified);
}

TEST(NmeaSentenceTest, RefusesMalformedChecksums) {
  EXPECT_EQ(refusal("$CATXF,2*5"), ErrorKind::kMalformedChecksum);
  EXPECT_EQ(refusal("$CATXF,2*"), ErrorKind::kMalformedChecksum);
  EXPECT_EQ(refusal("$CATXF,2*5G"), ErrorKind::kMalformedChecksum);
  EXPECT_EQ(refusal("$CATXF,2*566"), ErrorKind::kMalformedChecksum);
  EXPECT_EQ(refusal("$CATXF,2*56*56"), ErrorKind::kMalformedChecksum);
}

TEST(NmeaSentenceTest, RefusesLinesThatAreNotSentences) {
  EXPECT_EQ(refusal(""), ErrorKind::kEmpty);
  EXPECT_EQ(refusal("\r\n"), ErrorKind::kEmpty);
  EXPECT_EQ(refusal("CATXF,2*56"), ErrorKind::kNoDollar);
  EXPECT_EQ(refusal("$CATXF,2$CATXF,2*56"), ErrorKind::kEmbeddedDollar);
  EXPECT_EQ(refusal(std::string("$CATXF,\x01\xff*56", 11)), ErrorKind::kNonPrintable);
  EXPECT_EQ(refusal(std::string("$CA\0XF,2*56", 11)), ErrorKind::kNonPrintable);
  EXPECT_EQ(refusal("$CA-XF,2*2F"), ErrorKind::kBadAddress);
  EXPECT_EQ(refusal("$,2*1E"), ErrorKind::kBadAddress);
  EXPECT_EQ(refusal("$*00"), ErrorKind::kBadAddress);
}

TEST(NmeaSentenceTest, OtherWellFormedAddressesAreReportedAsUnsupportedToBeSkipped) {
  EXPECT_EQ(refusal("$PUBX,00*33"), ErrorKind::kUnsupportedAddress);
  EXPECT_EQ(refusal("$PUBX,00*34"), ErrorKind::kBadChecksum);  // damage is damage
}

TEST(NmeaSentenceTest, RefusesLinesLongerThanTheBound) {
  std::string body = "CARXD,1,2,1,1," + std::string(kMaxLineLength, 'A');
  EXPECT_EQ(refusal("$" + body), ErrorKind::kTooLong);
  // The longest accepted line is exactly the bound.
  std::string longest = "$CARXD,1,2,1,1,";
  longest += std::string(kMaxLineLength - longest.size() - 3, 'A');
  longest += "*00";
  ASSERT_EQ(longest.size(), kMaxLineLength);
  EXPECT_EQ(refusal(longest), ErrorKind::kBadChecksum);  // past the length check
}

TEST(NmeaSentenceTest, SerializeRefusesFieldsASentenceCannotCarry) {
  EXPECT_THROW(serialize(Sentence{"CC", "CFG", {"A,B"}}), std::invalid_argument);
  EXPECT_THROW(serialize(Sentence{"CC", "CFG", {"A*B"}}), std::invalid_argument);
  EXPECT_THROW(serialize(Sentence{"CC", "CFG", {"A$B"}}), std::invalid_argument);
  EXPECT_THROW(serialize(Sentence{"CC", "CFG", {"A\r"}}), std::invalid_argument);
  EXPECT_THROW(serialize(Sentence{"CCX", "CFG", {}}), std::invalid_argument);
  EXPECT_THROW(serialize(Sentence{"C-", "CFG", {}}), std::invalid_argument);
}

TEST(NmeaSentenceTest, ErrorTextsQuoteBinaryBytesReadably) {
  Result<Sentence> parsed = parse_sentence(std::string("$CA\x07XF*00", 9));
  ASSERT_FALSE(parsed.ok());
  EXPECT_NE(parsed.error().text.find("\\x07"), std::string::npos) << parsed.error().text;
  EXPECT_NE(parsed.error().text.find("column 4"), std::string::npos) << parsed.error().text;
}

}  // namespace
}  // namespace acomms::micromodem
