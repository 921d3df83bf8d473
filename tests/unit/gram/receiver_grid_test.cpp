// ReceiverGrid: the O(1) lookups on evenly spaced ranges and depths give
// exactly the binary search's answer (also at and next to every grid value,
// and outside the grid), and the slot order is a permutation of the
// receivers that keeps each column's depths together.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "gram/receiver_grid.h"

namespace acomms::gram {
namespace {

std::size_t reference(const std::vector<double>& sorted, double x) {
  return static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), x) - sorted.begin());
}

// Values at, between, one ulp either side of, and beyond every element.
std::vector<double> probes(const std::vector<double>& sorted) {
  std::vector<double> out = {-1e9, sorted.front() - 1.0, sorted.back() + 1.0, 1e9,
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const double x = sorted[i];
    out.insert(out.end(), {x, std::nextafter(x, -1e300), std::nextafter(x, 1e300)});
    if (i + 1 < sorted.size()) out.push_back(0.5 * (x + sorted[i + 1]));
  }
  return out;
}

void expect_same_as_binary_search(const std::vector<double>& sorted, double inverse_step) {
  for (double x : probes(sorted))
    EXPECT_EQ(ReceiverColumn::first_at_or_after(sorted, inverse_step, x), reference(sorted, x)) << "x = " << x;
}

TEST(GramReceiverGrid, EvenLookupMatchesTheBinarySearch) {
  // Spacings that are not exact in binary, as BELLHOP-style linspace gives.
  for (const auto& [first, last, n] : {std::tuple{0.01, 3.0, 300}, std::tuple{0.0, 110.0, 111},
                                       std::tuple{0.0, 100000.0, 1001}, std::tuple{-5.0, 7.3, 13}}) {
    std::vector<double> x(n);
    for (int i = 0; i < n; ++i) x[i] = first + (last - first) * i / (n - 1);
    expect_same_as_binary_search(x, (n - 1) / (last - first));
  }
}

TEST(GramReceiverGrid, UnevenValuesUseTheBinarySearch) {
  expect_same_as_binary_search({0.0, 1.0, 1.5, 10.0, 10.0, 200.0}, 0.0);
}

Environment grid(std::vector<double> ranges_m, std::vector<double> depths_m) {
  Environment env;
  for (double r : ranges_m) env.add_receiver_range_m(r);
  for (double z : depths_m) env.add_receiver_depth_m(z);
  return env;
}

TEST(GramReceiverGrid, EvenGridColumnsFindTheirReceivers) {
  std::vector<double> ranges, depths;
  for (int i = 0; i < 300; ++i) ranges.push_back(10.0 + 2990.0 * i / 299);
  for (int i = 0; i < 111; ++i) depths.push_back(110.0 * i / 110);
  const ReceiverGrid g(grid(ranges, depths));
  ASSERT_EQ(g.column_count(), 300u);
  for (double r : probes(ranges)) EXPECT_EQ(g.first_column_at_or_after(r), reference(ranges, r)) << "r = " << r;
  for (double z : probes(depths))
    EXPECT_EQ(g.first_depth_at_or_after(g.columns()[7], z), reference(depths, z)) << "z = " << z;
}

TEST(GramReceiverGrid, SlotsArePerColumnAndCoverEveryReceiverOnce) {
  // A grid with a range listed twice: that column holds every depth twice,
  // so the columns do not share one depth list.
  for (const Environment& env : {grid({100, 300, 200}, {5, 1, 3}), grid({100, 200, 200}, {5, 1, 3})}) {
    const ReceiverGrid g(env);
    std::vector<std::size_t> outputs = g.slot_outputs();
    ASSERT_EQ(outputs.size(), g.size());
    std::size_t slot = 0;
    for (const ReceiverColumn& column : g.columns()) {
      EXPECT_EQ(column.first_slot, slot);
      EXPECT_EQ(g.depths(column), column.depth_m);
      for (std::size_t k = 0; k < column.index.size(); ++k) EXPECT_EQ(outputs[slot + k], column.index[k]);
      slot += column.index.size();
    }
    std::sort(outputs.begin(), outputs.end());
    std::vector<std::size_t> all(g.size());
    std::iota(all.begin(), all.end(), 0);
    EXPECT_EQ(outputs, all);
  }
}

// What the columns of a rectilinear grid are, stated the slow way: a map
// from each range to its (depth, output index) pairs, sorted. The grid
// builds them without the per-column sort; the columns must be the same.
std::vector<std::pair<double, std::vector<std::pair<double, std::size_t>>>> reference_columns(
    const std::vector<double>& ranges, const std::vector<double>& depths) {
  std::map<double, std::vector<std::pair<double, std::size_t>>> by_range;
  for (std::size_t ir = 0; ir < ranges.size(); ++ir)
    for (std::size_t iz = 0; iz < depths.size(); ++iz)
      by_range[ranges[ir]].emplace_back(depths[iz], iz * ranges.size() + ir);
  std::vector<std::pair<double, std::vector<std::pair<double, std::size_t>>>> out;
  for (auto& [range, entries] : by_range) {
    std::sort(entries.begin(), entries.end());
    out.emplace_back(range, entries);
  }
  return out;
}

TEST(GramReceiverGrid, RectilinearColumnsAreTheSortedDepthsOfEachDistinctRange) {
  // Unsorted ranges and depths, a range listed twice (and -0 beside 0, one
  // key), a depth listed twice, and a plain even grid.
  // The last field: whether each column's depths are evenly spaced.
  const std::vector<std::tuple<std::vector<double>, std::vector<double>, bool>> grids = {
      {{300, 100, 200, 100, 0.0, -0.0, 50}, {30, 5, 1, 5, 12.5}, false},
      {{10, 20, 30, 40}, {8, 2, 4, 0, 6}, true},
      {{1395.97, 5, 2790.5}, {100, 50}, false},  // two depths: no step taken
  };
  for (const auto& [ranges, depths, even] : grids) {
    const ReceiverGrid g(grid(ranges, depths));
    const auto expected = reference_columns(ranges, depths);
    ASSERT_EQ(g.columns().size(), expected.size());
    ASSERT_EQ(g.size(), ranges.size() * depths.size());
    for (std::size_t j = 0; j < expected.size(); ++j) {
      const ReceiverColumn& column = g.columns()[j];
      const auto& [range, entries] = expected[j];
      EXPECT_EQ(column.range_m, range) << "column " << j;
      EXPECT_EQ(std::signbit(column.range_m), std::signbit(range)) << "column " << j << ": the first listed is the key";
      EXPECT_EQ(g.column_range(j), range);
      ASSERT_EQ(column.depth_m.size(), entries.size()) << "column " << j;
      for (std::size_t k = 0; k < entries.size(); ++k) {
        EXPECT_EQ(column.depth_m[k], entries[k].first) << "column " << j << " depth " << k;
        EXPECT_EQ(column.index[k], entries[k].second) << "column " << j << " depth " << k;
      }
      // A column holding a range twice holds each depth twice: not even.
      const bool column_even = even && entries.size() == depths.size();
      EXPECT_EQ(column.uniform_spacing, column_even ? 2.0 : 0.0) << "column " << j;
      EXPECT_EQ(column.inverse_spacing, column_even ? 0.5 : 0.0) << "column " << j;
    }
  }
}

}  // namespace
}  // namespace acomms::gram
