// Receiver columns: shared/spec/gram.md §1.5, §4.9.
#include "gram/receiver_grid.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace acomms::gram {
namespace {

// The step of `x` if its values are evenly spaced (within rounding), else 0.
double even_step(const std::vector<double>& x) {
  if (x.size() < 3) return 0;
  const double step = (x.back() - x.front()) / static_cast<double>(x.size() - 1);
  if (!(step > 0)) return 0;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (std::abs(x[i] - x[i - 1] - step) > 1e-9 * step) return 0;
  return step;
}

}  // namespace

std::size_t ReceiverColumn::binary_search(const std::vector<double>& sorted, double x) {
  return static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), x) - sorted.begin());
}

void ReceiverGrid::add_column(double range, const std::vector<std::pair<double, std::size_t>>& entries) {
  ReceiverColumn column{range, {}, {}};
  column.depth_m.reserve(entries.size());
  column.index.reserve(entries.size());
  for (const auto& [z, index] : entries) {
    column.depth_m.push_back(z);
    column.index.push_back(index);
  }
  const double spacing = even_step(column.depth_m);
  add_column(std::move(column), spacing);
}

void ReceiverGrid::add_column(ReceiverColumn column, double depth_spacing) {
  column.uniform_spacing = depth_spacing;
  column.inverse_spacing = depth_spacing > 0 ? 1.0 / depth_spacing : 0.0;
  column.first_slot = slot_outputs_.size();
  slot_outputs_.insert(slot_outputs_.end(), column.index.begin(), column.index.end());
  ranges_.push_back(column.range_m);
  columns_.push_back(std::move(column));
}

ReceiverGrid::ReceiverGrid(const Environment& env) {
  const std::size_t nz = env.receiver_depth_m_size(), nr = env.receiver_range_m_size();
  if (env.irregular_receivers()) {
    std::map<double, std::vector<std::pair<double, std::size_t>>> by_range;
    for (std::size_t i = 0; i < nr; ++i)
      by_range[env.receiver_range_m(i)].emplace_back(env.receiver_depth_m(i), i);
    size_ = nr;
    for (auto& [range, entries] : by_range) {
      std::sort(entries.begin(), entries.end());
      add_column(range, entries);
    }
  } else {
    // Output order: depth-major, [iz · nr + ir]. The same columns as a map
    // of ranges to sorted (depth, index) pairs would give, without sorting
    // each column (that took a tenth of a 201 × 1000 run, on one thread):
    // the depths are sorted once, ties by iz, which orders their indices
    // iz · nr + ir; equal ranges form one column, the first listed its key,
    // each depth then holding every such range's receiver in ir order.
    std::vector<std::pair<double, std::size_t>> depths(nz);
    for (std::size_t iz = 0; iz < nz; ++iz) depths[iz] = {env.receiver_depth_m(iz), iz};
    std::sort(depths.begin(), depths.end());
    std::vector<std::size_t> by_range(nr);
    std::iota(by_range.begin(), by_range.end(), std::size_t{0});
    std::stable_sort(by_range.begin(), by_range.end(), [&](std::size_t a, std::size_t b) {
      return env.receiver_range_m(a) < env.receiver_range_m(b);
    });
    size_ = nz * nr;
    slot_outputs_.reserve(size_);
    std::vector<double> sorted_depths(nz);
    for (std::size_t k = 0; k < nz; ++k) sorted_depths[k] = depths[k].first;
    const double depth_spacing = even_step(sorted_depths);
    std::vector<std::pair<double, std::size_t>> entries;
    for (std::size_t first = 0; first < nr;) {
      const double range = env.receiver_range_m(by_range[first]);
      std::size_t last = first + 1;
      while (last < nr && !(range < env.receiver_range_m(by_range[last]))) ++last;
      if (last == first + 1) {  // the usual case: a range listed once
        ReceiverColumn column{range, sorted_depths, std::vector<std::size_t>(nz)};
        for (std::size_t k = 0; k < nz; ++k) column.index[k] = depths[k].second * nr + by_range[first];
        add_column(std::move(column), depth_spacing);
        first = last;
        continue;
      }
      entries.clear();
      for (const auto& [z, iz] : depths)
        for (std::size_t k = first; k < last; ++k) entries.emplace_back(z, iz * nr + by_range[k]);
      add_column(range, entries);
      first = last;
    }
  }
  if (const double step = even_step(ranges_); step > 0) inverse_range_step_ = 1.0 / step;
  // The columns of a rectilinear grid hold the same sorted depths (unless a
  // range is listed twice: then that column holds them twice).
  const bool same_depths = std::all_of(columns_.begin(), columns_.end(), [&](const ReceiverColumn& c) {
    return c.depth_m == columns_.front().depth_m;
  });
  if (!columns_.empty() && same_depths) shared_depths_ = columns_.front().depth_m;
}

}  // namespace acomms::gram
