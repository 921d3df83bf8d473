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
  observed_.fill(0);
}

void AdaptiveModel::observe(int axis, int32_t innovation) {
  tables_[axis].increment(symbol_of(innovation));
  if (++observed_[axis] >= kForgetAfter) {
    std::vector<int64_t> halved(tables_[axis].size());
    for (size_t s = 0; s < halved.size(); ++s) halved[s] = static_cast<int64_t>(tables_[axis].frequency(s) - 1) / 2;
    set_counts(axis, halved, 0);
  }
  assert(tables_[axis].total() <= dccl::arith::kMaxTotalFrequency);
}

void AdaptiveModel::set_counts(int axis, const std::vector<int64_t>& counts, size_t from) {
  const size_t bins = static_cast<size_t>(d_max_ - d_min_);
  std::vector<uint32_t> frequencies(bins);
  observed_[axis] = 0;
  for (size_t s = 0; s < bins; ++s) {
    frequencies[s] = static_cast<uint32_t>(counts[from + s] + 1);
    observed_[axis] += counts[from + s];
  }
  tables_[axis] = dccl::arith::FrequencyTable(frequencies);
}

std::vector<int64_t> AdaptiveModel::statistics() const {
  std::vector<int64_t> out;
  for (const auto& table : tables_)
    for (size_t s = 0; s < table.size(); ++s) out.push_back(static_cast<int64_t>(table.frequency(s)) - 1);
  return out;
}

bool AdaptiveModel::restore_statistics(const std::vector<int64_t>& statistics) {
  const size_t bins = static_cast<size_t>(d_max_ - d_min_);
  if (statistics.size() != kAxes * bins) return false;
  for (int axis = 0; axis < kAxes; ++axis) {
    int64_t sum = 0;
    for (size_t s = 0; s < bins; ++s) {
      const int64_t n = statistics[axis * bins + s];
      if (n < 0 || n >= kForgetAfter) return false;
      sum += n;
    }
    if (sum >= kForgetAfter) return false;
  }
  for (int axis = 0; axis < kAxes; ++axis) set_counts(axis, statistics, axis * bins);
  return true;
}

LearnedModel::LearnedModel(int32_t d_min, int32_t d_max)
    : ProbabilityModel(d_min, d_max),
      cache_(d_min, d_max),
      tables_{dccl::arith::FrequencyTable(ones(d_min, d_max)), dccl::arith::FrequencyTable(ones(d_min, d_max)),
              dccl::arith::FrequencyTable(ones(d_min, d_max))} {
  reset();
}

void LearnedModel::reset() {
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
  if (axis.count >= kForgetAfter) {
    // Integer halving (towards zero), the same on both ends; the variance
    // estimate stays non-negative (table() clamps the spread at 0).
    axis.count /= 2;
    axis.sum /= 2;
    axis.sum_of_squares /= 2;
    for (uint32_t& n : axis.histogram) n /= 2;
  }
}

std::vector<int64_t> LearnedModel::statistics() const {
  std::vector<int64_t> out;
  for (const Axis& axis : axes_) {
    out.insert(out.end(), {axis.count, axis.sum, axis.sum_of_squares});
    for (uint32_t n : axis.histogram) out.push_back(n);
  }
  return out;
}

bool LearnedModel::restore_statistics(const std::vector<int64_t>& statistics) {
  const size_t bins = static_cast<size_t>(d_max_ - d_min_);
  const size_t per_axis = 3 + bins;
  if (statistics.size() != kAxes * per_axis) return false;
  // What count innovations within the bounds can sum to: keeps table()'s
  // integer arithmetic within range for any stored bytes.
  const __int128 bound = std::max<int64_t>(-int64_t{d_min_}, d_max_);
  for (int a = 0; a < kAxes; ++a) {
    const int64_t* v = &statistics[a * per_axis];
    if (v[0] < 0 || v[0] >= kForgetAfter || v[1] < -v[0] * bound || v[1] > v[0] * bound || v[2] < 0 ||
        v[2] > v[0] * bound * bound)
      return false;
    int64_t sum = 0;
    for (size_t s = 0; s < bins; ++s) {
      if (v[3 + s] < 0 || v[3 + s] >= kForgetAfter) return false;
      sum += v[3 + s];
    }
    if (sum >= kForgetAfter) return false;
  }
  for (int a = 0; a < kAxes; ++a) {
    const int64_t* v = &statistics[a * per_axis];
    Axis& axis = axes_[a];
    axis.count = v[0];
    axis.sum = v[1];
    axis.sum_of_squares = v[2];
    for (size_t s = 0; s < bins; ++s) axis.histogram[s] = static_cast<uint32_t>(v[3 + s]);
  }
  return true;
}

}  // namespace acomms::telemetry
