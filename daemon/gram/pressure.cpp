// Depth <-> pressure: shared/spec/gram.md §2.3.
#include "gram/pressure.h"

#include <cmath>
#include <numbers>

namespace acomms::gram {
namespace {

double sin2(double latitude_deg) {
  const double s = std::sin(latitude_deg * std::numbers::pi / 180.0);
  return s * s;
}

// d(depth)/d(pressure) of the UNESCO formula, for Newton's method.
double unesco_depth_derivative(double p, double latitude_deg) {
  const double h = 1e-3;
  return (unesco_depth_from_pressure(p + h, latitude_deg) -
          unesco_depth_from_pressure(p - h, latitude_deg)) / (2 * h);
}

}  // namespace

double unesco_depth_from_pressure(double p, double latitude_deg) {
  const double x = sin2(latitude_deg);
  const double g = 9.780318 * (1.0 + (5.2788e-3 + 2.36e-5 * x) * x) + 1.092e-6 * p;
  return (((-1.82e-15 * p + 2.279e-10) * p - 2.2512e-5) * p + 9.72659) * p / g;
}

double unesco_pressure_from_depth(double depth_m, double latitude_deg) {
  double p = depth_m / 0.99;
  // Converges in 3-4 steps; the extra ones cost nothing and make the bound sure.
  for (int i = 0; i < 8; ++i) {
    const double residual = unesco_depth_from_pressure(p, latitude_deg) - depth_m;
    p -= residual / unesco_depth_derivative(p, latitude_deg);
    if (std::abs(residual) < 1e-9) break;
  }
  return p;
}

double saunders_depth_from_pressure(double p, double latitude_deg) {
  const double c1 = (5.92 + 5.25 * sin2(latitude_deg)) * 1e-3;
  const double c2 = 2.21e-6;
  return (1.0 - c1) * p - c2 * p * p;
}

double saunders_pressure_from_depth(double depth_m, double latitude_deg) {
  const double c1 = (5.92 + 5.25 * sin2(latitude_deg)) * 1e-3;
  const double c2 = 2.21e-6;
  return ((1.0 - c1) - std::sqrt((1.0 - c1) * (1.0 - c1) - 4.0 * c2 * depth_m)) / (2.0 * c2);
}

}  // namespace acomms::gram
