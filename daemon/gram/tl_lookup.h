// Transmission loss at any (range, depth) from a model grid.
//
// Problem: a simulated packet travels between positions that never fall on
// the model's receiver grid. Decision: bilinear interpolation between the
// four surrounding receivers, in INTENSITY (10^(−TL/10)), like every other
// average in GRAM: a shadow (+inf) corner contributes 0, it does not make
// the whole cell silent. Outside the grid the nearest edge is used (clamped
// in range and depth); the range-0 column (NaN, no value on the source
// axis) is skipped, so ranges below the first positive grid range take
// that range's value. Thread-safe: pure functions.
#pragma once

#include "gram/transmission_loss.h"

namespace acomms::gram {

// TL (dB) at (range_m, depth_m); +inf where no beam reaches. Throws
// std::invalid_argument for an irregular list or a grid with no positive range.
double tl_at(const TransmissionLoss& tl, double range_m, double depth_m);

}  // namespace acomms::gram
