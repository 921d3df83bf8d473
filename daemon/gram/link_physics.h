// Whether a packet gets through, from the physics: SNR = SL − TL − NL and a
// reception curve per rate (spec §6.5 with AG = 0, a single hydrophone),
// with the site's corrections (site_correction.h) when it has them.
//
// Problem: the simulator and the depth-adaptation evaluation must judge
// packets the same way, from a source level, a noise level and the model's
// transmission loss. Decision: one small value type both use; NL is either
// given or the band level of the noise model (§6.6) over the receiver's
// band around the carrier, with the wind of a sea state (sea_state.h).
// Thread-safe: a value type; pure functions.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "gram/reception_curve.h"
#include "gram/site_correction.h"

namespace acomms::gram {

inline constexpr double kDefaultSourceLevelDb = 190.0;  // dB re 1 µPa at 1 m

// The noise model's inputs: sea state, and the band [centre ± band/2].
struct NoiseModelInput {
  int sea_state = 2;
  double centre_hz = 25000;
  double band_hz = 4160;  // the Micro-Modem's FH-FSK band
  double shipping = 0.5;  // [0, 1]
};

// The band when none is given: the Micro-Modem's 4160 Hz at its 25 kHz
// carrier, and the same fraction (16.64%) of any other carrier, so that a
// 500 Hz environment gets a 83.2 Hz band rather than an impossible one.
double default_band_hz(double centre_hz);

// The depth spacing of a link model's receiver grid when none is given:
// 2 m, or a hundredth of the water column where that is coarser (deep
// water: 50 m in 5000 m), so that any environment gets a grid of at most
// about a hundred depths.
double default_depth_step_m(double water_depth_m);

// NL (dB re 1 µPa) of the noise model. Throws std::invalid_argument naming
// the bad field (`prefix` + sea_state / centre_hz / band_hz / shipping).
double modelled_noise_level_db(const NoiseModelInput& input, const std::string& prefix = "");

struct LinkPhysics {
  double source_level_db = kDefaultSourceLevelDb;
  double noise_level_db = 0;                  // NL in the receiver's band (ambient)
  std::map<std::int32_t, ReceptionCurve> curves;  // per rate; missing: the default
  SiteCorrection site;  // excess loss and own-ship noise (site_correction.h)

  const ReceptionCurve& curve(std::int32_t rate) const;
};

struct LinkOutcome {
  double tl_db = 0;        // the model's, without the site's excess loss
  double snr_db = 0;       // SL − (TL + excess) − NL_total (−inf in shadow)
  double probability = 0;  // that the packet decodes
};

// `rate` < 0 (a mini-packet) uses rate 0's curve.
LinkOutcome link_outcome(const LinkPhysics& physics, double tl_db, std::int32_t rate);

}  // namespace acomms::gram
