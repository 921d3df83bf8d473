// Sonar equation: shared/spec/gram.md §6.5.
#include "gram/sonar_equation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "gram/ambient_noise.h"
#include "gram/validation_text.h"

namespace acomms::gram {

std::optional<std::string> validate_sonar(const SonarOptions& o) {
  if (auto e = require_finite("sonar.source_level_db", o.source_level_db)) return e;
  if (auto e = require_finite("sonar.array_gain_db", o.array_gain_db)) return e;
  if (auto e = require_finite("sonar.threshold_db", o.threshold_db)) return e;
  if (auto e = validate_site_correction(o.site, "sonar.")) return e;
  if (o.noise_decrease_db_per_km)
    if (auto e =
            require_at_least("sonar.noise_decrease_db_per_km", *o.noise_decrease_db_per_km, 0.0))
      return e;
  if (o.noise_level_db) return require_finite("sonar.noise_level_db", *o.noise_level_db);
  const NoiseBand& b = o.band;
  if (auto e = require_greater("sonar.band.f_lo_khz", b.f_lo_khz, 0.0)) return e;
  if (auto e = require_greater("sonar.band.f_hi_khz", b.f_hi_khz, b.f_lo_khz))
    return *e + " (sonar.band.f_lo_khz)";
  if (auto e = require_at_least("sonar.band.shipping", b.shipping, 0.0)) return e;
  if (b.shipping > 1)
    return "sonar.band.shipping = " + format_number(b.shipping) + " must be at most 1";
  return require_at_least("sonar.band.wind_mps", b.wind_mps, 0.0);
}

double signal_excess_db(double sl, double h, double nl, double ag) { return sl - h - nl + ag; }

double noise_level_db(const SonarOptions& o) {
  if (auto e = validate_sonar(o)) throw std::invalid_argument(*e);
  if (o.noise_level_db) return *o.noise_level_db;
  return ambient_noise_band_level(o.band.f_lo_khz, o.band.f_hi_khz, o.band.shipping,
                                  o.band.wind_mps);
}

std::vector<double> signal_excess_objective(std::span<const double> se_db, double threshold_db) {
  double best = -std::numeric_limits<double>::infinity();
  for (double se : se_db)
    if (!std::isnan(se)) best = std::max(best, se);
  std::vector<double> o;
  for (double se : se_db) {
    if (!(best > threshold_db) || !(se > threshold_db)) {
      o.push_back(0.0);  // below the threshold, a shadow, or no depth clears it
      continue;
    }
    o.push_back(std::clamp((se - threshold_db) / (best - threshold_db), 0.0, 1.0));
  }
  return o;
}

}  // namespace acomms::gram
