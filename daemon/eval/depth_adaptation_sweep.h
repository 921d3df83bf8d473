#pragma once
// "Which case am I in?": the depth-adaptation replay (depth_adaptation.h)
// run across a range of one quantity, so an operator sees at what margin
// adapting the depth starts to matter on their environment.
//
// Schneider (2013, §4.3.5) found what the replay shows: where every depth
// has margin, adaptation cannot pay; where the link is marginal it does.
// Which of the two a site is in depends on numbers a user rarely knows
// well (the noise, the excess loss a calibration measures), so the sweep
// steps one of them and reports, per value, the adaptive vehicle's receipt
// and the best fixed depth's, each with its standard error, and the margin
// between them in standard errors.
//
// Standard errors: a receipt p over n packets has SE sqrt(p (1 − p) / n).
// The margin divides the difference by sqrt(SE_a² + SE_f²), the SE of a
// difference of independent samples. The replay draws the same random
// numbers for every strategy (common random numbers), which correlates the
// two positively, so the true SE of the difference is smaller: the margin
// printed is conservative.
//
// Thread-safe: as run_depth_adaptation (nothing shared between calls).

#include <string>
#include <vector>

#include "eval/depth_adaptation.h"

namespace acomms::eval {

enum class SweepQuantity {
  kNoise,       // the band noise level NL, dB re 1 µPa (replaces the noise model)
  kExcessLoss,  // the site's excess loss, dB (gram/site_correction.h)
};

struct SweepRange {
  double from = 0, to = 0, step = 1;
};

struct SweepPoint {
  double value = 0;
  double adaptive = 0, adaptive_se = 0;
  std::string best_fixed;  // the fixed depth receiving most at this value
  double fixed = 0, fixed_se = 0;
  double margin_se = 0;  // (adaptive − fixed) / sqrt(SE_a² + SE_f²); 0 when both SEs are 0
};

// "noise" or "excess-loss"; throws std::invalid_argument naming both.
SweepQuantity sweep_quantity_from_string(const std::string& name);
// "FROM:TO:STEP" (dB); throws std::invalid_argument saying what is wrong:
// not three numbers, STEP ≤ 0, TO < FROM, or more than kMaxSweepPoints.
SweepRange parse_sweep_range(const std::string& text);
inline constexpr int kMaxSweepPoints = 200;
// The values FROM, FROM + STEP, ..., up to TO (within a millionth of STEP).
std::vector<double> sweep_values(const SweepRange& range);

// Runs the replay at each value (the rest of `config` as given).
std::vector<SweepPoint> run_depth_adaptation_sweep(const gram::Environment& env, const DepthAdaptationConfig& config,
                                                   const gram::Environment* vehicle_model, SweepQuantity quantity,
                                                   const SweepRange& range);

std::string format_sweep_table(SweepQuantity quantity, const DepthAdaptationConfig& config,
                               const std::vector<SweepPoint>& points);
std::string format_sweep_json(SweepQuantity quantity, const std::vector<SweepPoint>& points);

}  // namespace acomms::eval
