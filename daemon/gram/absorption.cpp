// Thorp and Francois-Garrison absorption: shared/spec/gram.md §3.1, §3.2.
#include "gram/absorption.h"

#include <cmath>

namespace acomms::gram {

double thorp_absorption(double f) {
  const double f2 = f * f;
  return 3.3e-3 + 0.11 * f2 / (1.0 + f2) + 44.0 * f2 / (4100.0 + f2) + 3.0e-4 * f2;
}

double thorp_absorption_stojanovic(double f) {
  const double f2 = f * f;
  return 0.11 * f2 / (1.0 + f2) + 44.0 * f2 / (4100.0 + f2) + 2.75e-4 * f2 + 0.003;
}

FrancoisGarrisonTerms francois_garrison_absorption(double f, double t, double s, double ph,
                                                   double z) {
  const double theta = 273.0 + t;
  const double c = 1412.0 + 3.21 * t + 1.19 * s + 0.0167 * z;
  const double f2 = f * f;

  const double a1 = 8.86 / c * std::pow(10.0, 0.78 * ph - 5.0);
  const double f1 = 2.8 * std::sqrt(s / 35.0) * std::pow(10.0, 4.0 - 1245.0 / theta);

  const double a2 = 21.44 * s / c * (1.0 + 0.025 * t);
  const double f2_relax = 8.17 * std::pow(10.0, 8.0 - 1990.0 / theta) / (1.0 + 0.0018 * (s - 35.0));
  const double p2 = 1.0 - 1.37e-4 * z + 6.2e-9 * z * z;

  const double p3 = 1.0 - 3.83e-5 * z + 4.9e-10 * z * z;
  const double a3 = t <= 20.0 ? 4.937e-4 - 2.59e-5 * t + 9.11e-7 * t * t - 1.50e-8 * t * t * t
                              : 3.964e-4 - 1.146e-5 * t + 1.45e-7 * t * t - 6.5e-10 * t * t * t;
  FrancoisGarrisonTerms terms;
  terms.boric_db_per_km = a1 * f1 * f2 / (f2 + f1 * f1);
  terms.mgso4_db_per_km = a2 * p2 * f2_relax * f2 / (f2 + f2_relax * f2_relax);
  terms.water_db_per_km = a3 * p3 * f2;
  return terms;
}

}  // namespace acomms::gram
