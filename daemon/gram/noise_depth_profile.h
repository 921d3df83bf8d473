// Depth dependence of the ambient noise level in deep water (spec §6.6).
//
// Problem: in deep water, surface-generated noise reaches depth along the
// same paths as sound from the surface; below the critical depth (where the
// sound speed regains the maximum found above the channel axis) those paths
// are cut and the noise level falls, so a deep vehicle hears better than H̄
// alone says. Decision, after the example of Schneider (2013): NL(d) = NL₀
// down to the critical depth d_c, then NL₀ − g_NL (d − d_c) with g_NL in
// dB/km (spec default 3 dB/km). d_c is found on the profile's points with
// c linear between them (for a spline profile this approximates within one
// node interval, well inside the model's noise uncertainty). No critical depth
// (the profile never regains the speed, e.g. shallow water, or its least
// speed is at the surface, so there is no channel): NL is constant,
// as the thesis's modelling of shallow water (≈ 1 dB variation) supports.
// Thread-safe: pure functions.
#pragma once

#include <optional>

#include "acomms/gram/environment.pb.h"

namespace acomms::gram {

inline constexpr double kDefaultNoiseDecreaseDbPerKm = 3.0;

// d_c of the environment's profile, or nullopt if there is none.
std::optional<double> critical_depth(const Environment& env);

double noise_level_at_depth(double nl0_db, double depth_m, std::optional<double> critical_depth_m,
                            double decrease_db_per_km);

}  // namespace acomms::gram
