#include "telemetry/gaussian_table.h"

#include <algorithm>
#include <cmath>

#include "telemetry/deterministic_math.h"

namespace acomms::telemetry {

int64_t sigma16_of_variance(double variance) {
  if (!(variance > 0)) return kMinSigma16;
  // sqrt is correctly rounded (IEEE-754), so this is the same everywhere.
  const double sigma16 = 16 * std::sqrt(variance);
  if (sigma16 >= static_cast<double>(kMaxSigma16)) return kMaxSigma16;
  return std::clamp(round_to_int(sigma16), kMinSigma16, kMaxSigma16);
}

std::vector<uint32_t> gaussian_frequencies(int32_t d_min, int32_t d_max, int64_t mean16,
                                           int64_t sigma16) {
  constexpr int kPanels = 8;  // Simpson panels per unit bin (even)
  constexpr double kNegligible = 40.5;
  const size_t bins = static_cast<size_t>(d_max - d_min);
  const double mean = static_cast<double>(mean16) / 16;
  const double sigma = static_cast<double>(sigma16) / 16;
  const double inv_two_var = 1 / (2 * sigma * sigma);
  // density at the panel edges, shared between neighbouring bins
  std::vector<double> density(bins * kPanels + 1);
  for (size_t j = 0; j < density.size(); ++j) {
    const double u = (d_min - 0.5 + static_cast<double>(j) / kPanels) - mean;
    // Beyond 9 sigma the density (< e^-40.5) cannot lift a bin above its
    // floor of 1 (it would need 2^-16 of the total): skip the exp.
    const double x = u * u * inv_two_var;
    density[j] = x > kNegligible ? 0 : exp_neg(x);
  }
  std::vector<double> weight(bins);
  double total = 0;
  for (size_t b = 0; b < bins; ++b) {
    const double* f = &density[b * kPanels];
    double sum = f[0] + f[kPanels];
    for (int i = 1; i < kPanels; ++i) sum += (i % 2 == 1 ? 4 : 2) * f[i];
    weight[b] = sum;
    total += sum;
  }
  std::vector<uint32_t> frequencies(bins, 1);
  if (total > 0) {
    for (size_t b = 0; b < bins; ++b)
      frequencies[b] += static_cast<uint32_t>(std::floor(weight[b] / total * kGaussianScale));
  }
  return frequencies;
}

const dccl::arith::FrequencyTable& GaussianTableCache::get(int64_t mean16, int64_t sigma16) {
  const uint64_t key = (static_cast<uint64_t>(mean16) << 32) ^ static_cast<uint64_t>(sigma16);
  auto it = tables_.find(key);
  if (it != tables_.end()) return it->second;
  return tables_
      .emplace(key, dccl::arith::FrequencyTable(gaussian_frequencies(d_min_, d_max_, mean16, sigma16)))
      .first->second;
}

}  // namespace acomms::telemetry
