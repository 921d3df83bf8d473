// The conformance-vector line format (`acommsctl dccl encode` input).
#include "dccl/vector_line.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace acomms::dccl {
namespace {

TEST(VectorLine, SplitsTypeTextAndHex) {
  VectorLine v = parse_vector_line("|gv.Num4| ri: -5 od: nan ru: 6 => 145f00010003  ");
  EXPECT_EQ(v.type, "gv.Num4");
  EXPECT_EQ(v.text, " ri: -5 od: nan ru: 6");
  EXPECT_EQ(v.hex, "145f00010003");
}

TEST(VectorLine, HexIsOptional) {
  VectorLine v = parse_vector_line("|gv.Str4| r: \"abc\"");
  EXPECT_EQ(v.text, " r: \"abc\"");
  EXPECT_EQ(v.hex, "");
}

TEST(VectorLine, ArrowInsideAStringLiteralIsPartOfTheString) {
  EXPECT_EQ(parse_vector_line("|gv.Str4| r: \"a => b\"").text, " r: \"a => b\"");
  VectorLine v = parse_vector_line(R"(|gv.Str4| s: 'x => "y' r: "q\" => " => 1a)");
  EXPECT_EQ(v.text, R"( s: 'x => "y' r: "q\" => ")");
  EXPECT_EQ(v.hex, "1a");
}

TEST(VectorLine, RejectsALineWithoutAType) {
  EXPECT_THROW(parse_vector_line("gv.Str4 r: \"a\""), std::invalid_argument);
  EXPECT_THROW(parse_vector_line("|gv.Str4 r: \"a\""), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::dccl
