// Ambient noise: the Wenz curves in closed form (Coates 1990, as given by
// Stojanovic 2007).
//
// Problem: the signal excess a depth offers is SL − TL − NL; NL comes from
// turbulence, shipping, wind and thermal noise. The closed forms give PSDs
// in dB re 1 µPa²/Hz; the band level integrates the PSD numerically over
// the receiver's band (log-spaced Simpson rule, so narrow and decade-wide
// bands are treated alike). Thread-safe: pure functions. Spec: §6.6.
#pragma once

namespace acomms::gram {

struct NoiseSpectrum {
  double turbulence_db = 0;
  double shipping_db = 0;
  double wind_db = 0;
  double thermal_db = 0;
  double total_db = 0;
};

// PSD at f (kHz) for shipping activity in [0, 1] and wind speed (m/s).
NoiseSpectrum ambient_noise_psd(double f_khz, double shipping, double wind_mps);

// Band level NL (dB re 1 µPa) over [f_lo, f_hi] kHz.
double ambient_noise_band_level(double f_lo_khz, double f_hi_khz, double shipping,
                                double wind_mps);

}  // namespace acomms::gram
