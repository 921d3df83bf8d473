// Depth low-pass: shared/spec/gram.md §6.4.
#include "gram/depth_lowpass.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

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

namespace {

constexpr double kUniformTolerance = 1e-6;  // relative, on the depth spacing

// Linear interpolation of samples y at z0 + j·dz, clamped at both ends.
double sample(const std::vector<double>& y, double z0, double dz, double z) {
  const double u = (z - z0) / dz;
  if (u <= 0) return y.front();
  const auto j = static_cast<std::size_t>(u);
  if (j + 1 >= y.size()) return y.back();
  const double t = u - static_cast<double>(j);
  return y[j] + t * (y[j + 1] - y[j]);
}

}  // namespace

std::vector<double> lowpass_on_depths(std::span<const double> depth_m,
                                      std::span<const double> values,
                                      const LowpassOptions& options) {
  if (depth_m.size() != values.size())
    throw std::invalid_argument("the low-pass got " + std::to_string(values.size()) +
                                " values for " + std::to_string(depth_m.size()) + " depths");
  if (depth_m.size() < 2) return {values.begin(), values.end()};
  double smallest = depth_m[1] - depth_m[0];
  bool uniform = true;
  for (std::size_t k = 1; k < depth_m.size(); ++k) {
    const double d = depth_m[k] - depth_m[k - 1];
    if (!(d > 0))
      throw std::invalid_argument("the low-pass needs increasing depths: depth " +
                                  format_number(depth_m[k]) + " m follows " +
                                  format_number(depth_m[k - 1]) + " m");
    uniform = uniform && std::abs(d - (depth_m[1] - depth_m[0])) <= kUniformTolerance * d;
    smallest = std::min(smallest, d);
  }
  if (uniform && smallest <= kMaxLowpassStep_m * (1 + kUniformTolerance))
    return lowpass_over_depth(values, smallest, options);
  // Resample: uniform steps of at most min(smallest, 10 m) ending exactly at the last depth.
  const double span = depth_m.back() - depth_m.front();
  const double target = std::min(smallest, kMaxLowpassStep_m);
  const auto steps = static_cast<std::size_t>(std::ceil(span / target - kUniformTolerance));
  const double dz = span / static_cast<double>(steps);
  std::vector<double> uniform_values;
  std::size_t k = 0;
  for (std::size_t j = 0; j <= steps; ++j) {
    const double z = depth_m.front() + dz * static_cast<double>(j);
    while (k + 2 < depth_m.size() && depth_m[k + 1] <= z) ++k;
    const double t = std::clamp((z - depth_m[k]) / (depth_m[k + 1] - depth_m[k]), 0.0, 1.0);
    uniform_values.push_back(values[k] + t * (values[k + 1] - values[k]));
  }
  const std::vector<double> y = lowpass_over_depth(uniform_values, dz, options);
  std::vector<double> out;
  for (double z : depth_m) out.push_back(sample(y, depth_m.front(), dz, z));
  return out;
}

}  // namespace acomms::gram
