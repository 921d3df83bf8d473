#include "telemetry/probability_models.h"

#include <algorithm>
#include <cassert>

#include "telemetry/deterministic_math.h"

namespace acomms::telemetry {
namespace {

std::vector<uint32_t> ones(int32_t d_min, int32_t d_max) {
  return std::vector<uint32_t>(static_cast<size_t>(d_max - d_min), 1);
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

}  // namespace acomms::telemetry
