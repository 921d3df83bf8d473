#pragma once
// The excess loss without the survivors' bias: a censored (Tobit-style)
// maximum-likelihood fit that counts the packets that did not decode.
//
// Problem: a modem measures an SNR only for packets it decoded. Where the
// link scatters about the model (measured = predicted + offset + ε, ε of
// standard deviation σ) and runs near its threshold, the packets that
// decoded are those whose ε happened to be high: the mean of measured −
// predicted over decoded packets (eval/link_calibration.h, fit_excess_loss)
// overstates the offset, by more the closer to the threshold and the larger
// σ. A site calibrated that way looks better than it is.
//
// Decision: fit the offset μ and σ jointly with a probit reception curve
// against the true SNR s (P(decode | s) = Φ((s − s50)/w)), every packet
// with a prediction p counting:
//   decoded, measured m:  φ((m − p − μ)/σ)/σ · Φ((m − s50)/w)
//   lost (or decoded with no SNR reported): 1 − Φ(z) (or Φ(z)),
//     z = (p + μ − s50)/√(σ² + w²)   (the integral over s, in closed form).
// A hard threshold (classic Tobit) is the limit w → 0. The four parameters
// (μ, ln σ, s50, ln w) maximise the log-likelihood by Nelder–Mead from the
// decoded-only estimate; μ's 95% interval comes from the numerical Hessian.
// Refused (nullopt, the reason in `why`) when there is nothing to correct
// for or the data cannot carry the fit: fewer than kMinMeasured measured
// packets, fewer than kMinEachOutcome lost ones, a decoded-only spread
// under 0.05 dB (no scatter: no bias), or no convergence.
//
// Thread-safe: a pure function.
#include <optional>
#include <string>
#include <vector>

#include "eval/link_calibration.h"

namespace acomms::eval {

struct CensoredExcessLossFit {
  std::size_t packets = 0, measured = 0;  // all used, and those with a measured SNR
  double offset_db = 0;                   // μ: mean(measured − predicted) over every packet sent
  double spread_db = 0;                   // σ
  double offset_ci95_db = 0;              // ± of μ
  double snr50_db = 0, width_db = 0;      // the probit curve against the true SNR
};

std::optional<CensoredExcessLossFit> fit_censored_excess_loss(const std::vector<PacketSample>& samples,
                                                              std::string* why);

}  // namespace acomms::eval
