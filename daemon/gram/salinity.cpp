// PSS-78: shared/spec/gram.md §2.2.
#include "gram/salinity.h"

#include <cmath>

namespace acomms::gram {

double practical_salinity(double r, double t, double p) {
  static constexpr double a[] = {0.0080, -0.1692, 25.3851, 14.0941, -7.0261, 2.7081};
  static constexpr double b[] = {0.0005, -0.0056, -0.0066, -0.0375, 0.0636, -0.0144};
  constexpr double k = 0.0162;
  const double rt_of_t =
      0.6766097 + t * (2.00564e-2 + t * (1.104259e-4 + t * (-6.9698e-7 + t * 1.0031e-9)));
  const double rp = 1.0 + p * (2.070e-5 + p * (-6.370e-10 + p * 3.989e-15)) /
                              (1.0 + 3.426e-2 * t + 4.464e-4 * t * t + (4.215e-1 - 3.107e-3 * t) * r);
  const double rt = r / (rp * rt_of_t);
  const double root = std::sqrt(rt);
  double sum_a = 0.0, sum_b = 0.0;
  for (int i = 5; i >= 0; --i) {
    sum_a = sum_a * root + a[i];
    sum_b = sum_b * root + b[i];
  }
  return sum_a + (t - 15.0) / (1.0 + k * (t - 15.0)) * sum_b;
}

}  // namespace acomms::gram
