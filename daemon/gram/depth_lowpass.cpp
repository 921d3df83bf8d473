// Depth low-pass: shared/spec/gram.md §6.4.
#include "gram/depth_lowpass.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "gram/validation_text.h"

namespace acomms::gram {

std::optional<std::string> validate_lowpass(const LowpassOptions& options) {
  return require_greater("lowpass.cutoff_per_m", options.cutoff_per_m, 0.0);
}

std::vector<double> lowpass_over_depth(std::span<const double> values, double step_m,
                                       const LowpassOptions& options) {
  if (auto e = validate_lowpass(options)) throw std::invalid_argument(*e);
  if (auto e = require_greater("depth step_m", step_m, 0.0)) throw std::invalid_argument(*e);
  std::vector<double> y(values.begin(), values.end());
  if (y.empty()) return y;
  const double a = 1.0 - std::exp(-2.0 * std::numbers::pi * options.cutoff_per_m * step_m);
  for (std::size_t j = 1; j < y.size(); ++j) y[j] = y[j - 1] + a * (y[j] - y[j - 1]);
  if (options.zero_phase)
    for (std::size_t j = y.size() - 1; j-- > 0;) y[j] = y[j + 1] + a * (y[j] - y[j + 1]);
  return y;
}

}  // namespace acomms::gram
