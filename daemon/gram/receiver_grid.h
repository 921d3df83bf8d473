// Receivers arranged for the range-interval beam influence.
//
// Problem: each ray segment must find the receivers whose range falls in its
// interval and, at each such range, those within the beam's reach in depth —
// without scanning the whole grid. Decision: receivers are grouped into
// columns of equal range, sorted by range, each with its depths sorted; both
// a rectilinear grid and an irregular list map to this. `index` is the
// receiver's position in the caller's output order.
// Immutable after construction; shared by tracing threads.
#pragma once

#include <cstddef>
#include <vector>

#include "acomms/gram/environment.pb.h"

namespace acomms::gram {

struct ReceiverColumn {
  double range_m;
  std::vector<double> depth_m;      // ascending
  std::vector<std::size_t> index;   // output index of each depth
  double uniform_spacing = 0;       // the depth step if evenly spaced, else 0
};

class ReceiverGrid {
 public:
  explicit ReceiverGrid(const Environment& env);

  const std::vector<ReceiverColumn>& columns() const { return columns_; }
  std::size_t size() const { return size_; }
  // First column with range ≥ r.
  std::size_t first_column_at_or_after(double r) const;

 private:
  std::vector<ReceiverColumn> columns_;
  std::size_t size_ = 0;
};

}  // namespace acomms::gram
