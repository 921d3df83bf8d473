// Volume absorption of sound in sea water, dB/km.
//
// Problem: above a few kHz, absorption dominates transmission loss at
// acoustic-modem ranges. Thorp (in the form of Jensen et al. 2011, which is
// also what BELLHOP's 'T' option applies) depends on frequency only;
// Francois & Garrison 1982 adds temperature, salinity, pH and depth.
// Thread-safe: pure functions. Spec: shared/spec/gram.md §3.
#pragma once

namespace acomms::gram {

// dB per neper × 1000 m: converts dB/km to Np/m (spec §3.3).
inline constexpr double kDbPerKmPerNeperPerM = 8685.889638;

// Thorp, Jensen et al. 2011 form (the model's), dB/km; f in kHz.
double thorp_absorption(double f_khz);
// The Stojanovic 2007 variant (2.75e-4 f² + 0.003), for comparison only.
double thorp_absorption_stojanovic(double f_khz);

struct FrancoisGarrisonTerms {
  double boric_db_per_km = 0;
  double mgso4_db_per_km = 0;
  double water_db_per_km = 0;
  double total() const { return boric_db_per_km + mgso4_db_per_km + water_db_per_km; }
};

// Francois & Garrison 1982: f kHz, T °C, S ‰, pH, depth m.
FrancoisGarrisonTerms francois_garrison_absorption(double f_khz, double t_degc, double s_ppt,
                                                   double ph, double depth_m);

}  // namespace acomms::gram
