// What a real site adds to the model: an excess loss and the vehicle's own
// noise (issue "the model meets the sea"; Schneider (2013) §4.3.5).
//
// Problem: the propagation model's TL and the ambient-noise model never
// match a real site. At GLINT10 the modems failed at transmission losses
// the flat-surface model does not reach within 3 km; Schneider names the
// rough sea surface (scattering the model leaves out) and the vehicle's own
// hull and machinery. A user who has measured their link (acommsctl link
// calibrate) needs a place to put what they measured, so that the
// simulator, the depth-adaptation replay and the depth objective's sonar
// equation all judge packets the same, corrected way.
//
// Decision: two numbers, applied where SNR is formed and nowhere else:
//   SNR = SL − (TL + excess_loss) − NL_total,
//   NL_total = 10 log10(10^(NL_ambient/10) + 10^(NL_own/10)),
// that is, the own-ship level is a second, independent noise source in the
// receiver's band (powers add), constant with depth (it travels with the
// vehicle), while the ambient level may vary with depth. excess_loss may be
// negative: a calibration can find the model pessimistic.
//
// Thread-safe: a value type; pure functions.
#pragma once

#include <optional>
#include <string>

namespace acomms::gram {

struct SiteCorrection {
  double excess_loss_db = 0;                // dB added to every TL
  std::optional<double> own_ship_noise_db;  // dB re 1 µPa in the band; unset: none

  // NL_total from the ambient band level (the power sum above).
  double total_noise_db(double ambient_noise_db) const;
};

// Why `site` cannot be used (a non-finite value), naming the field as
// `prefix` + excess_loss_db / own_ship_noise_db; nullopt when it can.
std::optional<std::string> validate_site_correction(const SiteCorrection& site, const std::string& prefix);

// Powers add: 10 log10(10^(a/10) + 10^(b/10)), exact for either far below
// the other (no overflow for levels in dB).
double power_sum_db(double a_db, double b_db);

}  // namespace acomms::gram
