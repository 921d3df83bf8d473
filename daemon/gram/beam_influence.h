// What one ray segment contributes to the receivers near it.
//
// Problem: a ray carries amplitude and phase only along itself; the beam
// spreads them over its neighbourhood (hat or Gaussian weight, spec §4.8)
// with the paraxial travel time (§4.9). Decision: the range-interval
// ("Cartesian") method: a segment a→b serves the receivers with range in
// [min(r_a, r_b), max(r_a, r_b)) — half-open, so a receiver on a step point
// is counted once — and, in each such column, the depths within reach.
// Coherent runs add complex pressure, incoherent and semi-coherent runs add
// intensity weighted by w (not w², so the hats stay a partition of unity).
// Not thread-safe per target buffer; const otherwise.
#pragma once

#include <complex>
#include <span>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "gram/medium.h"
#include "gram/ray.h"
#include "gram/receiver_grid.h"

namespace acomms::gram {

// The beam's constants, from its launch.
struct BeamLaunch {
  double angle_rad;      // θ0
  double abs_cos_angle;  // |cos θ0|, for the ray amplitude
  double spacing_rad;    // Δθ of the fan
  double source_speed;   // c(z_s)
  double intensity_factor = 1.0;  // semi-coherent source pattern, else 1
};

class BeamInfluence {
 public:
  BeamInfluence(const Medium& medium, const ReceiverGrid& receivers, FieldMode mode,
                BeamShape shape);

  // Adds the segment's contribution to `pressure` (coherent) or `intensity`,
  // both in the grid's slot order (ReceiverColumn::first_slot).
  // Inline up to the test whether the segment spans a receiver column at
  // all: about half the steps of a run do not, and they should cost no call.
  void add(const RayPoint& a, const RayPoint& b, const BeamLaunch& beam,
           std::span<std::complex<double>> pressure, std::span<double> intensity) const {
    if (a.r == b.r) return;
    const double r_hi = a.r < b.r ? b.r : a.r;
    const std::size_t j = receivers_.first_column_at_or_after(a.r < b.r ? a.r : b.r);
    if (j >= receivers_.column_count() || receivers_.column_range(j) >= r_hi) return;
    add_columns(j, r_hi, a, b, beam, pressure, intensity);
  }

 private:
  // Columns j, j+1, ... with range below r_hi (at least column j).
  void add_columns(std::size_t j, double r_hi, const RayPoint& a, const RayPoint& b,
                   const BeamLaunch& beam, std::span<std::complex<double>> pressure,
                   std::span<double> intensity) const;

  const Medium& medium_;
  const ReceiverGrid& receivers_;
  FieldMode mode_;
  BeamShape shape_;
};

}  // namespace acomms::gram
