// Practical salinity (PSS-78) from a conductivity ratio.
//
// Problem: many CTDs log conductivity, not salinity; the sound-speed equation
// needs salinity. PSS-78 (Fofonoff & Millard 1983 §3) converts the ratio
// R = C / C(35, 15 °C, 0) at IPTS-68 temperature and sea pressure.
// Thread-safe: pure functions. Spec: shared/spec/gram.md §2.2.
#pragma once

namespace acomms::gram {

// Conductivity of standard sea water C(35, 15 °C, 0), mS/cm.
inline constexpr double kStandardConductivityMsPerCm = 42.914;

double practical_salinity(double conductivity_ratio, double t68_degc, double pressure_dbar);

}  // namespace acomms::gram
