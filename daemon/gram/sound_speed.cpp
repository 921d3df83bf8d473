// Sound speed equations: shared/spec/gram.md §2.4 (UNESCO) and §2.5 (Mackenzie).
#include "gram/sound_speed.h"

#include <cmath>

namespace acomms::gram {
namespace {

// Horner evaluation of c[0] + c[1] t + c[2] t² + ...
template <std::size_t N>
double polynomial(const double (&c)[N], double t) {
  double sum = 0.0;
  for (std::size_t i = N; i-- > 0;) sum = sum * t + c[i];
  return sum;
}

}  // namespace

double t68_from_t90(double t90_degc) { return 1.00024 * t90_degc; }

double unesco_sound_speed(double s, double t, double pressure_dbar) {
  static constexpr double C0[] = {1402.388, 5.03711, -5.80852e-2, 3.3420e-4, -1.47800e-6, 3.1464e-9};
  static constexpr double C1[] = {0.153563, 6.8982e-4, -8.1788e-6, 1.3621e-7, -6.1185e-10};
  static constexpr double C2[] = {3.1260e-5, -1.7107e-6, 2.5974e-8, -2.5335e-10, 1.0405e-12};
  static constexpr double C3[] = {-9.7729e-9, 3.8504e-10, -2.3643e-12};
  static constexpr double A0[] = {1.389, -1.262e-2, 7.164e-5, 2.006e-6, -3.21e-8};
  static constexpr double A1[] = {9.4742e-5, -1.2580e-5, -6.4885e-8, 1.0507e-8, -2.0122e-10};
  static constexpr double A2[] = {-3.9064e-7, 9.1041e-9, -1.6002e-10, 7.988e-12};
  static constexpr double A3[] = {1.100e-10, 6.649e-12, -3.389e-13};
  // The equation is written in bar.
  const double p = pressure_dbar / 10.0;
  const double cw = polynomial(C0, t) +
                    p * (polynomial(C1, t) + p * (polynomial(C2, t) + p * polynomial(C3, t)));
  const double a = polynomial(A0, t) +
                   p * (polynomial(A1, t) + p * (polynomial(A2, t) + p * polynomial(A3, t)));
  const double b = -1.922e-2 - 4.42e-5 * t + (7.3637e-5 + 1.7945e-7 * t) * p;
  const double d = 1.727e-3 - 7.9836e-6 * p;
  return cw + a * s + b * s * std::sqrt(s) + d * s * s;
}

double mackenzie_sound_speed(double t, double s, double d) {
  return 1448.96 + 4.591 * t - 5.304e-2 * t * t + 2.374e-4 * t * t * t + 1.340 * (s - 35.0) +
         1.630e-2 * d + 1.675e-7 * d * d - 1.025e-2 * t * (s - 35.0) - 7.139e-13 * t * d * d * d;
}

}  // namespace acomms::gram
