#include "telemetry/probability_models.h"

#include <algorithm>
#include <cassert>

#include "telemetry/deterministic_math.h"

namespace acomms::telemetry {
namespace {

std::vector<uint32_t> ones(int32_t d_min, int32_t d_max) {
  return std::vector<uint32_t>(static_cast<size_t>(d_max - d_min), 1);
}

// a / b rounded to nearest (halves up), b > 0, exact for negative a too.
int64_t divide_rounded(int64_t a, int64_t b) {
  const int64_t n = 2 * a + b, d = 2 * b;
  return n >= 0 ? n / d : -((-n + d - 1) / d);
}

}  // namespace

UniformModel::UniformModel(int32_t d_min, int32_t d_max)
    : ProbabilityModel(d_min, d_max), table_(ones(d_min, d_max)) {}

const dccl::arith::FrequencyTable& GaussianModel::table(int, double variance) {
  return cache_.get(0, sigma16_of_variance(variance));
}

AdaptiveModel::AdaptiveModel(int32_t d_min, int32_t d_max)
    : ProbabilityModel(d_min, d_max),
      tables_{dccl::arith::FrequencyTable(ones(d_min, d_max)), dccl::arith::FrequencyTable(ones(d_min, d_max)),
              dccl::arith::FrequencyTable(ones(d_min, d_max))} {}

void AdaptiveModel::reset() {
  for (auto& table : tables_) table = dccl::arith::FrequencyTable(ones(d_min_, d_max_));
}

void AdaptiveModel::observe(int axis, int32_t innovation) {
  tables_[axis].increment(symbol_of(innovation));
  assert(tables_[axis].total() <= dccl::arith::kMaxTotalFrequency);
}

LearnedModel::LearnedModel(int32_t d_min, int32_t d_max)
    : ProbabilityModel(d_min, d_max),
      cache_(d_min, d_max),
      tables_{dccl::arith::FrequencyTable(ones(d_min, d_max)), dccl::arith::FrequencyTable(ones(d_min, d_max)),
              dccl::arith::FrequencyTable(ones(d_min, d_max))} {
  reset();
}

void LearnedModel::reset() {
  cache_.trim();
  for (Axis& axis : axes_) axis = Axis{0, 0, 0, std::vector<uint32_t>(static_cast<size_t>(d_max_ - d_min_), 0)};
}

const dccl::arith::FrequencyTable& LearnedModel::table(int index, double variance) {
  const Axis& axis = axes_[index];
  const int64_t m = axis.count;
  const int64_t mean16 = divide_rounded(16 * axis.sum, m + kMeanPrior);
  // 256 sum (d - mean)^2 = 256 sum d^2 - 32 mean16 sum d + m mean16^2
  const int64_t spread256 = std::max<int64_t>(
      0, 256 * axis.sum_of_squares - 32 * mean16 * axis.sum + m * mean16 * mean16);
  const int64_t prior_sigma16 = sigma16_of_variance(variance);
  const int64_t var256 =
      divide_rounded(kVariancePrior * prior_sigma16 * prior_sigma16 + spread256, kVariancePrior + m);
  const int64_t sigma16 =
      std::clamp(static_cast<int64_t>(isqrt_rounded(static_cast<uint64_t>(var256))), kMinSigma16, kMaxSigma16);
  const dccl::arith::FrequencyTable& gaussian = cache_.get(mean16, sigma16);
  std::vector<uint32_t> frequencies(axis.histogram.size());
  for (size_t s = 0; s < frequencies.size(); ++s)
    frequencies[s] = static_cast<uint32_t>(gaussian.frequency(s)) + kCountWeight * axis.histogram[s];
  tables_[index] = dccl::arith::FrequencyTable(frequencies);
  assert(tables_[index].total() <= dccl::arith::kMaxTotalFrequency);
  return tables_[index];
}

void LearnedModel::observe(int index, int32_t innovation) {
  Axis& axis = axes_[index];
  ++axis.count;
  axis.sum += innovation;
  axis.sum_of_squares += int64_t{innovation} * innovation;
  ++axis.histogram[symbol_of(innovation)];
}

}  // namespace acomms::telemetry
