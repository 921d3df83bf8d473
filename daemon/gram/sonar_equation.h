// Passive sonar equation (Schneider (2013) eq. 4.7, spec §6.5) and the
// signal-excess objective.
//
// Problem: H̄ alone is a proxy for SNR only where the noise does not vary
// with depth (shallow water); with a source level and a noise level the
// vehicle can rank depths by the margin it actually has. Decision:
// SE = SL − H − NL + AG in dB; NL is either a constant or the band level of
// the Wenz/Coates model (§6.6, ambient_noise.h), optionally a per-depth
// vector supplied by the caller. The objective from SE mirrors eq. 4.3:
// O_SE(d) = clip((SE(d) − SE₀)/(SE₁ − SE₀), 0, 1) with SE₁ = max_d SE(d);
// if SE₁ ≤ SE₀ no depth clears the threshold and O_SE is 0 everywhere.
// Thread-safe: pure functions.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gram/site_correction.h"

namespace acomms::gram {

// The receiver band and conditions for the noise model.
struct NoiseBand {
  double f_lo_khz = 0;    // > 0
  double f_hi_khz = 0;    // > f_lo_khz
  double shipping = 0.5;  // [0, 1]
  double wind_mps = 0;    // ≥ 0
};

struct SonarOptions {
  double source_level_db = 0;            // SL, dB re 1 µPa at 1 m
  double array_gain_db = 0;              // AG, 0 for one hydrophone
  std::optional<double> noise_level_db;  // NL, dB re 1 µPa; if unset, from `band`
  NoiseBand band;
  double threshold_db = 0;  // SE₀, the decoding threshold
  // Deep water: NL falls by this many dB/km below the critical depth of the
  // environment's profile (noise_depth_profile.h; spec default 3). Unset:
  // NL is the same at every depth.
  std::optional<double> noise_decrease_db_per_km;
  // The site's excess loss (added to H) and own-ship noise (added to NL at
  // every depth, powers summed): site_correction.h.
  SiteCorrection site;
};

std::optional<std::string> validate_sonar(const SonarOptions& options);

// Eq. 4.7.
double signal_excess_db(double source_level_db, double h_db, double noise_level_db,
                        double array_gain_db);

// NL from the options (constant, or the band level of the noise model).
// Throws std::invalid_argument with validate_sonar's message.
double noise_level_db(const SonarOptions& options);

// O_SE per depth from SE per depth (−inf SE, a shadow, gives 0).
std::vector<double> signal_excess_objective(std::span<const double> se_db, double threshold_db);

}  // namespace acomms::gram
