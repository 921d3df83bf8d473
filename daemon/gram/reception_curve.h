// The chance that a packet decodes at a given SNR: what a simulator needs
// to let the physics, not a fixed loss rate, decide what gets through.
//
// Problem: a modem does not fail at one SNR; close to its threshold some
// packets decode and some do not. Decision: a logistic curve per rate,
//     P(decode | SNR) = 1 / (1 + exp(−k (SNR − SNR₅₀)))
// with SNR₅₀ the SNR at which half the packets decode and k the logistic
// rate in 1/dB (the curve rises from 12% to 88% over 4/k dB around SNR₅₀).
// Defaults (no measured curve given): SNR₅₀ = 10 dB for rate 0 (FH-FSK,
// and every mini-packet: polls and ACKs are FSK), 14 dB for the PSK rates
// 1..5, k = 1/dB — round figures, not a fit to a modem; a user with a
// measured curve should configure it.
// Thread-safe: pure functions.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace acomms::gram {

struct ReceptionCurve {
  double snr50_db = 10.0;     // SNR at which half the packets decode
  double slope_per_db = 1.0;  // k, > 0
};

inline constexpr double kDefaultFskSnr50Db = 10.0;
inline constexpr double kDefaultPskSnr50Db = 14.0;
inline constexpr double kDefaultSlopePerDb = 1.0;

// The default curve of `rate` (0: FSK; anything else: PSK).
ReceptionCurve default_reception_curve(std::int32_t rate);

// nullopt when usable, else a message naming the field and bound
// (`prefix` + "snr50_db" / "slope_per_db").
std::optional<std::string> validate_reception_curve(const ReceptionCurve& curve, const std::string& prefix);

// P(decode) in [0, 1]; an SNR of −inf (no path) gives 0, +inf gives 1.
double reception_probability(const ReceptionCurve& curve, double snr_db);

}  // namespace acomms::gram
