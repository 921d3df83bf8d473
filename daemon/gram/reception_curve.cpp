#include "gram/reception_curve.h"

#include <cmath>

namespace acomms::gram {

ReceptionCurve default_reception_curve(std::int32_t rate) {
  return {rate == 0 ? kDefaultFskSnr50Db : kDefaultPskSnr50Db, kDefaultSlopePerDb};
}

std::optional<std::string> validate_reception_curve(const ReceptionCurve& curve, const std::string& prefix) {
  if (!std::isfinite(curve.snr50_db) || std::abs(curve.snr50_db) > 200)
    return prefix + "snr50_db must be a finite SNR within ±200 dB, got " + std::to_string(curve.snr50_db);
  if (!(curve.slope_per_db > 0 && curve.slope_per_db <= 100))
    return prefix + "slope_per_db must be in (0, 100] per dB, got " + std::to_string(curve.slope_per_db);
  return std::nullopt;
}

double reception_probability(const ReceptionCurve& curve, double snr_db) {
  if (std::isnan(snr_db)) return 0.0;
  const double x = curve.slope_per_db * (snr_db - curve.snr50_db);
  // exp of a large positive x overflows to inf, giving 0 as it should.
  return 1.0 / (1.0 + std::exp(-x));
}

}  // namespace acomms::gram
