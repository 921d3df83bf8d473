// Receivers arranged for the range-interval beam influence.
//
// Problem: each ray segment must find the receivers whose range falls in its
// interval and, at each such range, those within the beam's reach in depth —
// without scanning the whole grid. Decision: receivers are grouped into
// columns of equal range, sorted by range, each with its depths sorted; both
// a rectilinear grid and an irregular list map to this. `index` is the
// receiver's position in the caller's output order; the model accumulates
// in "slot" order instead (column after column, first_slot + k), so a beam
// writes to adjacent memory and needs no index lookup, and the sums are
// moved to output order once at the end (slot_outputs()). Searches run once
// per ray step (millions of times per run): on evenly spaced ranges or
// depths the index is computed, then corrected by at most a step or two, so
// the answer is exactly the binary search's at O(1) cost.
// Immutable after construction; shared by tracing threads.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "acomms/gram/environment.pb.h"

namespace acomms::gram {

struct ReceiverColumn {
  double range_m;
  std::vector<double> depth_m;      // ascending
  std::vector<std::size_t> index;   // output index of each depth
  std::size_t first_slot = 0;       // slot of depth 0; depth k is first_slot + k
  double uniform_spacing = 0;       // the depth step if evenly spaced, else 0
  double inverse_spacing = 0;       // 1 / uniform_spacing, or 0

  // The search behind both lookups: `inverse_step` > 0 if `sorted` is
  // evenly spaced (1 / the step), else 0 (binary search).
  static std::size_t first_at_or_after(const std::vector<double>& sorted, double inverse_step, double x) {
    if (inverse_step <= 0) return binary_search(sorted, x);
    // Estimate, then move to the exact answer (the spacing is even to 1e-9
    // relative, so the estimate is off by at most one).
    const std::size_t n = sorted.size();
    const double at = (x - sorted.front()) * inverse_step;
    std::size_t i = !(at > 0) ? 0 : at >= static_cast<double>(n) ? n : static_cast<std::size_t>(at);
    while (i > 0 && sorted[i - 1] >= x) --i;
    while (i < n && sorted[i] < x) ++i;
    return i;
  }
  static std::size_t binary_search(const std::vector<double>& sorted, double x);
};

class ReceiverGrid {
 public:
  explicit ReceiverGrid(const Environment& env);

  const std::vector<ReceiverColumn>& columns() const { return columns_; }
  std::size_t size() const { return size_; }
  std::size_t column_count() const { return ranges_.size(); }
  // The column's depths: on a rectilinear grid one vector that all columns
  // share (equal to each column's depth_m), so the hot loop reads a few KB
  // that stay in cache rather than one copy per column.
  const std::vector<double>& depths(const ReceiverColumn& column) const {
    return shared_depths_.empty() ? column.depth_m : shared_depths_;
  }
  // First depth index of `column` with depth ≥ z (its size if none).
  std::size_t first_depth_at_or_after(const ReceiverColumn& column, double z) const {
    return ReceiverColumn::first_at_or_after(depths(column), column.inverse_spacing, z);
  }
  // Output index of each slot (size() of them).
  const std::vector<std::size_t>& slot_outputs() const { return slot_outputs_; }
  double column_range(std::size_t j) const { return ranges_[j]; }
  // First column with range ≥ r.
  std::size_t first_column_at_or_after(double r) const {
    return ReceiverColumn::first_at_or_after(ranges_, inverse_range_step_, r);
  }

 private:
  // Appends the column of `range` holding `entries` (depth, output index),
  // sorted.
  void add_column(double range, const std::vector<std::pair<double, std::size_t>>& entries);
  // Appends `column` (its depths and indices set) with its depth step
  // (even_step of its depths).
  void add_column(ReceiverColumn column, double depth_spacing);

  std::vector<ReceiverColumn> columns_;
  std::vector<double> ranges_;  // columns_[j].range_m, contiguous for the search
  std::vector<std::size_t> slot_outputs_;
  std::vector<double> shared_depths_;  // rectilinear grids only
  double inverse_range_step_ = 0;  // 1 / the range step if evenly spaced, else 0
  std::size_t size_ = 0;
};

}  // namespace acomms::gram
