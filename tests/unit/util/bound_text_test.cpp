// The words of a broken bound: the exact sentence, the interval's form and
// the numbers' shortest form.

#include "util/bound_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace acomms::util {
namespace {

TEST(BoundText, NamesTheFieldTheValueAndTheRule) {
  EXPECT_EQ(must_be("gram.workers", "0", within("1", "64")), "gram.workers = 0 must be within [1, 64]");
  EXPECT_EQ(must_be("horizon_s", "-1", "greater than 0"), "horizon_s = -1 must be greater than 0");
}

TEST(BoundText, WithinIncludesBothEnds) { EXPECT_EQ(within("-90", "90"), "within [-90, 90]"); }

TEST(BoundText, FormatNumberIsTheShortestStreamForm) {
  EXPECT_EQ(format_number(0), "0");
  EXPECT_EQ(format_number(0.5), "0.5");
  EXPECT_EQ(format_number(-3), "-3");
  EXPECT_EQ(format_number(1e6), "1e+06");
  EXPECT_EQ(format_number(1234.5678), "1234.57");
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_number(std::nan("")), "nan");
}

}  // namespace
}  // namespace acomms::util
