// Beam count: shared/spec/gram.md §4.7.
#include "gram/beam_fan.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gram/environment_validation.h"
#include "gram/sound_speed_profile.h"

namespace acomms::gram {

std::uint32_t automatic_beam_count(const Environment& env) {
  double r_max = 0;
  for (double r : env.receiver_range_m()) r_max = std::max(r_max, r);
  const SoundSpeedProfile ssp(env);
  const double zs = env.source_depth_m();
  const double c0 = ssp.at(zs, ssp.layer_at(zs, 1.0)).c;
  const double depth = deepest_bottom(env) - env.sound_speed(0).depth_m();
  const double by_wavelength = 0.3 * r_max * env.frequency_hz() / c0;
  const double by_depth = 10.0 * std::numbers::pi * r_max / depth;
  const double n = std::floor(std::max({300.0, by_wavelength, by_depth}));
  return static_cast<std::uint32_t>(std::min(n, 1.0e6));
}

std::uint32_t beam_count(const Environment& env) {
  return env.beam_count() > 0 ? env.beam_count() : automatic_beam_count(env);
}

}  // namespace acomms::gram
