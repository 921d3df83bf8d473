#include "gram/site_correction.h"

#include <algorithm>
#include <cmath>

#include "gram/validation_text.h"

namespace acomms::gram {

double power_sum_db(double a_db, double b_db) {
  const double hi = std::max(a_db, b_db), lo = std::min(a_db, b_db);
  if (std::isinf(lo) && lo < 0) return hi;  // no power from the quieter one
  // Factored by the louder so that 10^(x/10) never overflows.
  return hi + 10.0 * std::log10(1.0 + std::pow(10.0, (lo - hi) / 10.0));
}

double SiteCorrection::total_noise_db(double ambient_noise_db) const {
  return own_ship_noise_db ? power_sum_db(ambient_noise_db, *own_ship_noise_db) : ambient_noise_db;
}

std::optional<std::string> validate_site_correction(const SiteCorrection& site, const std::string& prefix) {
  if (auto e = require_finite(prefix + "excess_loss_db", site.excess_loss_db)) return e;
  if (site.own_ship_noise_db) return require_finite(prefix + "own_ship_noise_db", *site.own_ship_noise_db);
  return std::nullopt;
}

}  // namespace acomms::gram
