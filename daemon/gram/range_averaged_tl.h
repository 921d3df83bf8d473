// Range-averaged transmission loss H̄(d) (Schneider (2013) eq. 4.2, spec
// §6.2) and its average over sound-speed profile instances (eq. 4.4, spec
// §6.3).
//
// Problem: pointwise TL flickers by tens of dB between interference nulls a
// vehicle cannot steer by; what it can use is the loss it will see on
// average over the ranges it is about to cross. Decision: for each depth,
// average the INTENSITY |p|² = 10^(−TL/10) over the grid ranges r_j in the
// window [begin, end) (equal weights, as eq. 4.2), then convert back to dB.
// Averaging is always in intensity, never in dB (a null must not dominate).
//   - A range within 1 µm of a window edge counts as on it (grid ranges are
//     converted from km and may be off by a rounding error).
//   - Shadow receivers (TL = +inf) contribute intensity 0; receivers at
//     range 0 (NaN, no value) are left out of the mean.
//   - A depth whose intensities are all zero, or a window holding only the
//     range-0 column, gets H̄ = +inf (no depth can be scored there).
// Thread-safe: pure functions.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "gram/range_window.h"
#include "gram/transmission_loss.h"

namespace acomms::gram {

struct RangeAveragedTl {
  std::vector<double> depth_m;   // the grid's depths
  std::vector<double> h_bar_db;  // H̄(d) per depth
  std::size_t ranges_in_window = 0;
};

// Throws std::invalid_argument for an irregular receiver list, a malformed
// grid, or a window holding no grid range (message gives the window and the
// grid's range span).
RangeAveragedTl range_averaged_tl(const TransmissionLoss& tl, const RangeWindow& window);

// The smallest spacing between consecutive grid ranges (what a window must
// span to hold one range); throws std::invalid_argument with fewer than 2.
double grid_range_step(const TransmissionLoss& tl);

// Eq. 4.4 at one depth: H(d, i) for each instance i.
struct InstanceAverage {
  double h_n_db = 0;  // −10 log10(mean intensity)
  // The sensitivity band −10 log10(Ī ± σ_I), σ_I the population standard
  // deviation (1/n, matching the mean) of the intensities. low_db ≤ h_n_db ≤
  // high_db; when σ_I ≥ Ī the high edge is capped at kBandFloorDb.
  double band_low_db = 0;
  double band_high_db = 0;
};
inline constexpr double kBandFloorDb = 300.0;  // −10 log10(tiny), beyond any model TL

// Throws std::invalid_argument if `h_db` is empty or holds a NaN.
InstanceAverage average_over_instances(std::span<const double> h_db);

}  // namespace acomms::gram
