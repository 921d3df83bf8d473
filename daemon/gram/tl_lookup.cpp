#include "gram/tl_lookup.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace acomms::gram {
namespace {

// Index i and weight w such that x ≈ (1 − w) v[i] + w v[i + 1] (i + 1 may be
// i when clamped), over v[first..]. v ascending.
struct Bracket {
  std::size_t lo, hi;
  double w;
};

Bracket bracket(const std::vector<double>& v, std::size_t first, double x) {
  if (x <= v[first]) return {first, first, 0.0};
  if (x >= v.back()) return {v.size() - 1, v.size() - 1, 0.0};
  auto it = std::upper_bound(v.begin() + static_cast<std::ptrdiff_t>(first), v.end(), x);
  const std::size_t hi = static_cast<std::size_t>(it - v.begin());
  const std::size_t lo = hi - 1;
  const double span = v[hi] - v[lo];
  return {lo, hi, span > 0 ? (x - v[lo]) / span : 0.0};
}

double intensity(double tl_db) {
  if (std::isnan(tl_db) || std::isinf(tl_db)) return 0.0;
  return std::pow(10.0, -tl_db / 10.0);
}

}  // namespace

double tl_at(const TransmissionLoss& tl, double range_m, double depth_m) {
  if (tl.irregular) throw std::invalid_argument("tl_at needs a rectilinear receiver grid");
  const std::size_t nr = tl.range_m.size(), nz = tl.depth_m.size();
  if (nr == 0 || nz == 0 || tl.tl_db.size() != nr * nz)
    throw std::invalid_argument("tl_at: the TL grid's size does not match its ranges and depths");
  std::size_t first = 0;
  while (first < nr && !(tl.range_m[first] > 0)) ++first;
  if (first == nr) throw std::invalid_argument("tl_at: the grid has no receiver range above 0");
  const Bracket r = bracket(tl.range_m, first, range_m);
  const Bracket z = bracket(tl.depth_m, 0, depth_m);
  auto at = [&](std::size_t iz, std::size_t ir) { return intensity(tl.tl_db[iz * nr + ir]); };
  const double i = (1 - z.w) * ((1 - r.w) * at(z.lo, r.lo) + r.w * at(z.lo, r.hi)) +
                   z.w * ((1 - r.w) * at(z.hi, r.lo) + r.w * at(z.hi, r.hi));
  return i > 0 ? -10.0 * std::log10(i) : INFINITY;
}

}  // namespace acomms::gram
