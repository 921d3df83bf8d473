// Rayleigh reflection: shared/spec/gram.md §4.5.
#include "gram/reflection.h"

#include <cmath>

namespace acomms::gram {

std::complex<double> reflection_coefficient(const Boundary& boundary, double grazing,
                                            double water_speed, double omega) {
  switch (boundary.kind()) {
    case Boundary::VACUUM: return -1.0;
    case Boundary::RIGID: return 1.0;
    default: break;
  }
  const HalfSpace& h = boundary.half_space();
  const double k1 = omega / water_speed;
  const std::complex<double> k2(omega / h.speed_mps(), h.attenuation_np_per_m());
  const double kr = k1 * std::cos(grazing);
  const double kz1 = k1 * std::sin(grazing);
  std::complex<double> kz2 = std::sqrt(k2 * k2 - kr * kr);
  if (kz2.imag() < 0) kz2 = -kz2;
  const double rho2 = h.density_ratio();  // the water's density is 1
  const std::complex<double> num = rho2 * kz1 - kz2;
  const std::complex<double> den = rho2 * kz1 + kz2;
  // Only a matched, lossless half-space at exactly grazing incidence gets
  // here: it reflects nothing, like at every other angle.
  if (std::abs(den) == 0.0) return 0.0;
  return num / den;
}

}  // namespace acomms::gram
