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

ReceiverGrid::ReceiverGrid(const Environment& env) {
  std::map<double, std::vector<std::pair<double, std::size_t>>> by_range;
  const std::size_t nz = env.receiver_depth_m_size(), nr = env.receiver_range_m_size();
  if (env.irregular_receivers()) {
    for (std::size_t i = 0; i < nr; ++i)
      by_range[env.receiver_range_m(i)].emplace_back(env.receiver_depth_m(i), i);
    size_ = nr;
  } else {
    // Output order: depth-major, [iz · nr + ir].
    for (std::size_t ir = 0; ir < nr; ++ir)
      for (std::size_t iz = 0; iz < nz; ++iz)
        by_range[env.receiver_range_m(ir)].emplace_back(env.receiver_depth_m(iz), iz * nr + ir);
    size_ = nz * nr;
  }
  for (auto& [range, entries] : by_range) {
    std::sort(entries.begin(), entries.end());
    ReceiverColumn column{range, {}, {}};
    for (const auto& [z, index] : entries) {
      column.depth_m.push_back(z);
      column.index.push_back(index);
    }
    column.uniform_spacing = even_step(column.depth_m);
    if (column.uniform_spacing > 0) column.inverse_spacing = 1.0 / column.uniform_spacing;
    column.first_slot = slot_outputs_.size();
    slot_outputs_.insert(slot_outputs_.end(), column.index.begin(), column.index.end());
    ranges_.push_back(range);
    columns_.push_back(std::move(column));
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
