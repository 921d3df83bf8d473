#pragma once
// The four probability models (see probability_model.h for what each does
// and why). Only make_model and tests name these classes.

#include <array>
#include <vector>

#include "telemetry/gaussian_table.h"
#include "telemetry/probability_model.h"

namespace acomms::telemetry {

class UniformModel final : public ProbabilityModel {
 public:
  UniformModel(int32_t d_min, int32_t d_max);
  void reset() override {}
  const dccl::arith::FrequencyTable& table(int, double) override { return table_; }
  void observe(int, int32_t) override {}

 private:
  dccl::arith::FrequencyTable table_;
};

class GaussianModel final : public ProbabilityModel {
 public:
  GaussianModel(int32_t d_min, int32_t d_max) : ProbabilityModel(d_min, d_max), cache_(d_min, d_max) {}
  void reset() override {}
  void trim() override { cache_.trim(); }
  const dccl::arith::FrequencyTable& table(int axis, double variance) override;
  void observe(int, int32_t) override {}

 private:
  GaussianTableCache cache_;
};

class AdaptiveModel final : public ProbabilityModel {
 public:
  AdaptiveModel(int32_t d_min, int32_t d_max);
  void reset() override;
  const dccl::arith::FrequencyTable& table(int axis, double) override { return tables_[axis]; }
  void observe(int axis, int32_t innovation) override;
  // Per axis, per symbol: N_d.
  std::vector<int64_t> statistics() const override;
  bool restore_statistics(const std::vector<int64_t>& statistics) override;

 private:
  void set_counts(int axis, const std::vector<int64_t>& counts, size_t from);

  std::array<dccl::arith::FrequencyTable, kAxes> tables_;
  std::array<int64_t, kAxes> observed_{};  // sum of N_d per axis
};

// Ours. The adaptive model pays for its uniform start (on a short track, or
// after a fresh start). The
// innovations of a vehicle that mostly holds course are narrow and biased
// (a speed not quite the configured one, a Kalman filter that lags), which a
// Gaussian with a learned mean and variance captures after two or three
// samples, while the counts still catch what is not Gaussian (the yo-yo's
// turns). Per axis, over the m innovations d_i sent since the fresh start:
//   mean  = sum d_i / (m + kMeanPrior)                   (shrunk towards 0)
//   var   = (kVariancePrior v0 + sum (d_i - mean)^2) / (kVariancePrior + m)
//   f(d)  = G(mean, var)(d) + kCountWeight N_d
// with v0 the observer's variance and G the integer Gaussian table
// (gaussian_table.h). mean and var are computed in integers (sixteenths and
// 1/256 of a precision step), so both ends agree exactly.
class LearnedModel final : public ProbabilityModel {
 public:
  // Weights of the priors, in samples. Not sensitive: 1-4 and 1/8-2 for
  // the count weight move the generated AUV and glider tracks by < 0.4 bits.
  static constexpr int64_t kMeanPrior = 1;
  static constexpr int64_t kVariancePrior = 1;
  static constexpr uint32_t kCountWeight = kGaussianScale / 2;

  LearnedModel(int32_t d_min, int32_t d_max);
  void reset() override;
  void trim() override { cache_.trim(); }
  const dccl::arith::FrequencyTable& table(int axis, double variance) override;
  void observe(int axis, int32_t innovation) override;
  // Per axis: count, sum, sum of squares, then the histogram.
  std::vector<int64_t> statistics() const override;
  bool restore_statistics(const std::vector<int64_t>& statistics) override;

 private:
  struct Axis {
    int64_t count = 0;
    int64_t sum = 0;
    int64_t sum_of_squares = 0;
    std::vector<uint32_t> histogram;
  };
  GaussianTableCache cache_;
  std::array<Axis, kAxes> axes_;
  std::array<dccl::arith::FrequencyTable, kAxes> tables_;
};

}  // namespace acomms::telemetry
