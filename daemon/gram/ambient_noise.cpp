// Wenz/Coates noise: shared/spec/gram.md §6.6.
#include "gram/ambient_noise.h"

#include <cmath>

namespace acomms::gram {
namespace {

double power(double db) { return std::pow(10.0, db / 10.0); }

}  // namespace

NoiseSpectrum ambient_noise_psd(double f, double shipping, double wind) {
  NoiseSpectrum n;
  n.turbulence_db = 17.0 - 30.0 * std::log10(f);
  n.shipping_db = 40.0 + 20.0 * (shipping - 0.5) + 26.0 * std::log10(f) - 60.0 * std::log10(f + 0.03);
  n.wind_db = 50.0 + 7.5 * std::sqrt(wind) + 20.0 * std::log10(f) - 40.0 * std::log10(f + 0.4);
  n.thermal_db = -15.0 + 20.0 * std::log10(f);
  n.total_db = 10.0 * std::log10(power(n.turbulence_db) + power(n.shipping_db) +
                                 power(n.wind_db) + power(n.thermal_db));
  return n;
}

double ambient_noise_band_level(double f_lo, double f_hi, double shipping, double wind) {
  // ∫ N(f) df = ∫ N(f) f d(ln f): Simpson's rule on a uniform grid in ln f.
  constexpr int kIntervals = 2000;  // even
  const double u0 = std::log(f_lo), u1 = std::log(f_hi);
  const double h = (u1 - u0) / kIntervals;
  double sum = 0.0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double f = std::exp(u0 + i * h);
    const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += weight * power(ambient_noise_psd(f, shipping, wind).total_db) * f * 1000.0;  // df in Hz
  }
  return 10.0 * std::log10(sum * h / 3.0);
}

}  // namespace acomms::gram
