// The TL field as CSV: exact coordinates, TL as printf("%.3f") prints it,
// and the same bytes whatever the number of formatting threads.
#include "gram/tl_csv.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace acomms::gram {
namespace {

std::string joined(const std::vector<std::string>& blocks) {
  std::string all;
  for (const auto& b : blocks) all += b;
  return all;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string printf_fixed3(double v) {
  char text[400];
  std::snprintf(text, sizeof text, "%.3f", v);
  return text;
}

std::string fixed3(double v) {
  char text[400];
  return std::string(text, put_fixed3(text, v));
}

// A grid big enough to be split (more than one block's worth of rows), with
// coordinates that three significant digits would have rounded.
TransmissionLoss big_grid() {
  TransmissionLoss tl;
  for (int i = 0; i < 1001; ++i) tl.range_m.push_back(i * 1395.97 / 7);
  for (int i = 0; i < 101; ++i) tl.depth_m.push_back(0.3 + i * 2.5);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> db(-5.0, 180.0);
  for (std::size_t i = 0; i < tl.range_m.size() * tl.depth_m.size(); ++i) tl.tl_db.push_back(db(random));
  tl.tl_db[5] = std::numeric_limits<double>::infinity();
  tl.tl_db[0] = std::numeric_limits<double>::quiet_NaN();
  return tl;
}

TEST(GramTlCsv, IsTheSameBytesWhateverTheThreadCount) {
  const TransmissionLoss tl = big_grid();
  const std::string one = joined(tl_csv_blocks(tl, 1));
  EXPECT_EQ(tl_csv_blocks(tl, 2).size(), 2u);  // the field is split
  for (unsigned threads : {2u, 3u, 4u, 7u}) EXPECT_EQ(joined(tl_csv_blocks(tl, threads)), one) << threads << " threads";
}

TEST(GramTlCsv, CoordinatesReadBackAsTheModelsDoubles) {
  const TransmissionLoss tl = big_grid();
  const auto rows = lines(joined(tl_csv_blocks(tl, 2)));
  ASSERT_EQ(rows.size(), 1 + tl.tl_db.size());
  EXPECT_EQ(rows[0], "range_m,depth_m,tl_db");
  const std::size_t nr = tl.range_m.size();
  for (std::size_t i = 0; i < tl.tl_db.size(); i += 997) {
    const std::string& row = rows[1 + i];
    char* end = nullptr;
    const double r = std::strtod(row.c_str(), &end);
    ASSERT_EQ(*end, ',') << row;
    const double z = std::strtod(end + 1, &end);
    ASSERT_EQ(*end, ',') << row;
    EXPECT_EQ(r, tl.range_m[i % nr]) << row;  // exactly: depth-major rows
    EXPECT_EQ(z, tl.depth_m[i / nr]) << row;
  }
}

TEST(GramTlCsv, PrintsARangeWithAllItsDigitsAndTheTlWithThreeDecimals) {
  TransmissionLoss tl;
  tl.range_m = {0, 1395.97, 100000};
  tl.depth_m = {12.5};
  tl.tl_db = {std::numeric_limits<double>::quiet_NaN(), 63.21549, std::numeric_limits<double>::infinity()};
  EXPECT_EQ(joined(tl_csv_blocks(tl, 1)), "range_m,depth_m,tl_db\n0,12.5,\n1395.97,12.5,63.215\n100000,12.5,inf\n");
}

TEST(GramTlCsv, IrregularReceiversGiveOneRowEach) {
  TransmissionLoss tl;
  tl.irregular = true;
  tl.range_m = {100, 200.25};
  tl.depth_m = {10, 30};
  tl.tl_db = {40, 50.0005};  // 50.000500000000002 in binary: rounds up
  EXPECT_EQ(joined(tl_csv_blocks(tl, 3)), "range_m,depth_m,tl_db\n100,10,40.000\n200.25,30,50.001\n");
}

TEST(GramTlCsv, FixedThreeDecimalsIsPrintfsTextEvenAtHalves) {
  // Values on and next to the thousandths' halves, where v·1000 rounded
  // as a double could differ from the exact decimal rounding.
  std::vector<double> values = {0.0, -0.0, -0.0004, 0.0005, 0.0015, 0.0025, 1.0005, 2.5, 63.2155, 99.9995,
                                -12.3455, 1e12, -1e15, 1e300, 123456789.0125, 5e-324};
  for (int k = 0; k < 20000; ++k) {
    const double half = (k + 0.5) / 1000.0;
    values.push_back(half);
    values.push_back(std::nextafter(half, 0.0));
    values.push_back(std::nextafter(half, 1e9));
    values.push_back(-half);
  }
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> any(-400.0, 4000.0);
  for (int k = 0; k < 200000; ++k) values.push_back(any(random));
  for (double v : values) ASSERT_EQ(fixed3(v), printf_fixed3(v)) << std::hexfloat << v;
}

// Coordinates whose exact text is hundreds of characters (fixed notation
// of 1e-300 and 1e300) overrun the per-row room the formatter makes ahead:
// every row must still be whole, on any thread count; an empty field is
// the header alone.
TEST(GramTlCsv, LongCoordinatesAndAnEmptyFieldAreWrittenWhole) {
  TransmissionLoss tl;
  for (int i = 1; i <= 3; ++i) tl.range_m.push_back(i * 1e300);
  for (int i = 1; i <= 12000; ++i) tl.depth_m.push_back(i * 1e-300);
  for (std::size_t i = 0; i < tl.range_m.size() * tl.depth_m.size(); ++i) tl.tl_db.push_back(40.0 + i * 0.0007);
  std::string expected = "range_m,depth_m,tl_db\n";
  for (std::size_t iz = 0; iz < tl.depth_m.size(); ++iz)
    for (std::size_t ir = 0; ir < tl.range_m.size(); ++ir) {
      char text[800];
      char* end = std::to_chars(text, text + sizeof text, tl.range_m[ir], std::chars_format::fixed).ptr;
      *end++ = ',';
      end = std::to_chars(end, text + sizeof text, tl.depth_m[iz], std::chars_format::fixed).ptr;
      *end++ = ',';
      expected.append(text, end);
      expected += printf_fixed3(tl.tl_db[iz * tl.range_m.size() + ir]) + "\n";
    }
  EXPECT_GT(expected.size(), 36000u * 300);  // far beyond 28 bytes a row
  for (unsigned threads : {1u, 2u}) EXPECT_TRUE(joined(tl_csv_blocks(tl, threads)) == expected) << threads << " threads";
  EXPECT_EQ(joined(tl_csv_blocks(TransmissionLoss{}, 2)), "range_m,depth_m,tl_db\n");
}

}  // namespace
}  // namespace acomms::gram
