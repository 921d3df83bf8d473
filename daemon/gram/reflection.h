// Plane-wave reflection coefficient of a boundary at a grazing angle.
//
// Vacuum −1, rigid +1, fluid half-space by the Rayleigh formula with the
// branch Im k_z2 ≥ 0 (decaying into the half-space) and the half-space's
// complex speed c̃ = ω/(ω/c + iδ) for attenuation δ in Np/m (spec §1.3,
// §4.5). Thread-safe: pure function.
#pragma once

#include <complex>

#include "acomms/gram/environment.pb.h"

namespace acomms::gram {

// grazing_rad in [0, π/2]; water_speed is c at the boundary on the water side.
std::complex<double> reflection_coefficient(const Boundary& boundary, double grazing_rad,
                                            double water_speed, double omega);

}  // namespace acomms::gram
