// Receiver columns: shared/spec/gram.md §1.5, §4.9.
#include "gram/receiver_grid.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace acomms::gram {

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
    const auto& z = column.depth_m;
    if (z.size() >= 3) {
      const double step = (z.back() - z.front()) / static_cast<double>(z.size() - 1);
      bool even = step > 0;
      for (std::size_t i = 1; even && i < z.size(); ++i)
        even = std::abs(z[i] - z[i - 1] - step) <= 1e-9 * step;
      if (even) column.uniform_spacing = step;
    }
    columns_.push_back(std::move(column));
  }
}

std::size_t ReceiverGrid::first_column_at_or_after(double r) const {
  auto it = std::lower_bound(columns_.begin(), columns_.end(), r,
                             [](const ReceiverColumn& c, double x) { return c.range_m < x; });
  return static_cast<std::size_t>(it - columns_.begin());
}

}  // namespace acomms::gram
