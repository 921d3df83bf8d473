// Low-pass filter of the depth objective over depth (spec §6.4).
//
// Problem: in deep water the raw objective peaks just under a convergence-
// zone caustic, with the shadow zone directly above; a vehicle parked at the
// peak loses the link at the first error in the predicted caustic depth.
// The thesis prescribes a low-pass with a spatial cutoff of 1/50 m⁻¹
// "starting at the surface" and gives no more detail. Our reading (a design
// choice, fixed by the spec): a first-order recursive filter on a uniform
// depth grid, run from the shallowest depth downward,
//     a = 1 − exp(−2π f_c Δz),  y₀ = O₀,  y_j = y_{j−1} + a (O_j − y_{j−1}),
// so each output is a convex combination of inputs (stays in [0, 1]) and
// lags ≈ 1/(2π f_c) downward: the best depth moves below the caustic.
// `zero_phase` runs the same filter forward then backward (the backward pass
// starts from the forward output at the deepest point): no lag, for shallow
// water.
// On a depth grid that is uneven, or coarser than kMaxLowpassStep_m (where
// a → 1 and the filter would do nothing), the objective is resampled
// linearly onto a uniform grid from the first depth (step ≤ 10 m, as the
// spec recommends), filtered, and read back linearly at the given depths.
// Thread-safe: pure functions.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace acomms::gram {

struct LowpassOptions {
  double cutoff_per_m = 1.0 / 50.0;  // f_c, > 0
  bool zero_phase = false;
};

std::optional<std::string> validate_lowpass(const LowpassOptions& options);

// `values` sampled every `step_m` (> 0) from the shallowest depth down.
// Throws std::invalid_argument on a bad option or step.
std::vector<double> lowpass_over_depth(std::span<const double> values, double step_m,
                                       const LowpassOptions& options);

inline constexpr double kMaxLowpassStep_m = 10.0;

// The filter on ascending depths (strictly increasing; throws
// std::invalid_argument naming the first that is not).
std::vector<double> lowpass_on_depths(std::span<const double> depth_m,
                                      std::span<const double> values,
                                      const LowpassOptions& options);

}  // namespace acomms::gram
