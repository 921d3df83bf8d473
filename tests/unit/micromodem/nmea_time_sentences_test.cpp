// The MM2 clock sentences (spec §4.5): $CCTMS and its $CATMS reply, with
// the ISO 8601 time of the public transcripts (G-126: $CATMQ,2019-12-02T03:02:59Z,...).

#include <gtest/gtest.h>

#include "micromodem/nmea/sentence.h"
#include "micromodem/nmea/time_sentences.h"

namespace acomms::micromodem {
namespace {

TEST(NmeaTimeSentencesTest, CctmsCarriesTheIsoTimeAndTheMode) {
  TimeSet set{{2019, 12, 2, 3, 3, 0}, 0};
  std::string line = serialize(to_sentence(set));
  EXPECT_TRUE(line.starts_with("$CCTMS,2019-12-02T03:03:00Z,0*")) << line;
  EXPECT_TRUE(parse_sentence(line)) << "the checksum is right";
  auto parsed = parse_time_set(*parse_sentence("$CCTMS,2019-12-02T03:03:00Z,1", ChecksumRule::kOptional));
  ASSERT_TRUE(parsed) << parsed.error().text;
  EXPECT_EQ(parsed->time, (ClockTime{2019, 12, 2, 3, 3, 0}));
  EXPECT_EQ(parsed->mode, 1);
}

TEST(NmeaTimeSentencesTest, CatmsSaysWhetherItTimedOutAndTheTimeItKeeps) {
  auto reply = parse_time_set_reply(*parse_sentence("$CATMS,0,2019-12-02T03:02:59Z", ChecksumRule::kOptional));
  ASSERT_TRUE(reply) << reply.error().text;
  EXPECT_FALSE(reply->timed_out);
  EXPECT_EQ(iso_time_text(reply->time), "2019-12-02T03:02:59Z");
  auto timed_out = parse_time_set_reply(*parse_sentence("$CATMS,1,2019-12-02T03:02:59Z", ChecksumRule::kOptional));
  ASSERT_TRUE(timed_out);
  EXPECT_TRUE(timed_out->timed_out);
}

TEST(NmeaTimeSentencesTest, TimesThatAreNotWholeUtcSecondsAreRefusedNamingTheField) {
  for (const char* line : {"$CATMS,0,2019-12-02T03:02:59.5Z", "$CATMS,0,2019-12-02 03:02:59Z",
                           "$CATMS,0,2019-13-02T03:02:59Z", "$CATMS,0,2019-12-02T03:02:59+01", "$CATMS,0,",
                           "$CATMS,2,2019-12-02T03:02:59Z"}) {
    auto reply = parse_time_set_reply(*parse_sentence(line, ChecksumRule::kOptional));
    ASSERT_FALSE(reply) << line;
    EXPECT_NE(reply.error().text.find("CATMS field"), std::string::npos) << line << ": " << reply.error().text;
  }
  EXPECT_FALSE(parse_time_set_reply(*parse_sentence("$CATMS,0", ChecksumRule::kOptional)));
  EXPECT_FALSE(parse_time_set(*parse_sentence("$CCTMS,2019-12-02T03:03:00Z,2", ChecksumRule::kOptional)));
}

}  // namespace
}  // namespace acomms::micromodem
