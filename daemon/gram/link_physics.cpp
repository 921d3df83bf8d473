#include "gram/link_physics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gram/ambient_noise.h"
#include "gram/sea_state.h"
#include "gram/sonar_equation.h"

namespace acomms::gram {

double modelled_noise_level_db(const NoiseModelInput& in, const std::string& prefix) {
  const std::optional<double> wind = wind_speed_for_sea_state(in.sea_state);
  if (!wind)
    throw std::invalid_argument(prefix + "sea_state must be in 0.." + std::to_string(kMaxSeaState) + ", got " +
                                std::to_string(in.sea_state));
  if (!(in.centre_hz > 0 && in.centre_hz <= 1e6))
    throw std::invalid_argument(prefix + "centre_hz must be in (0, 1e6] Hz, got " + std::to_string(in.centre_hz));
  if (!(in.band_hz > 0 && in.band_hz < 2 * in.centre_hz))
    throw std::invalid_argument(prefix + "band_hz must be > 0 and below twice the centre frequency (" +
                                std::to_string(2 * in.centre_hz) + " Hz), got " + std::to_string(in.band_hz));
  if (!(in.shipping >= 0 && in.shipping <= 1))
    throw std::invalid_argument(prefix + "shipping must be in [0, 1], got " + std::to_string(in.shipping));
  const double lo_khz = (in.centre_hz - in.band_hz / 2) / 1000, hi_khz = (in.centre_hz + in.band_hz / 2) / 1000;
  return ambient_noise_band_level(lo_khz, hi_khz, in.shipping, *wind);
}

double default_band_hz(double centre_hz) { return 4160.0 * centre_hz / 25000.0; }

double default_depth_step_m(double water_depth_m) { return std::max(2.0, water_depth_m / 100.0); }

const ReceptionCurve& LinkPhysics::curve(std::int32_t rate) const {
  if (rate < 0) rate = 0;
  if (auto it = curves.find(rate); it != curves.end()) return it->second;
  static const ReceptionCurve kFsk = default_reception_curve(0), kPsk = default_reception_curve(1);
  return rate == 0 ? kFsk : kPsk;
}

LinkOutcome link_outcome(const LinkPhysics& physics, double tl_db, std::int32_t rate) {
  LinkOutcome out;
  out.tl_db = tl_db;
  // A shadow (TL = +inf) leaves no signal at all.
  out.snr_db = std::isfinite(tl_db) ? signal_excess_db(physics.source_level_db, tl_db + physics.site.excess_loss_db,
                                                       physics.site.total_noise_db(physics.noise_level_db), 0.0)
                                    : -INFINITY;
  out.probability = reception_probability(physics.curve(rate), out.snr_db);
  return out;
}

}  // namespace acomms::gram
