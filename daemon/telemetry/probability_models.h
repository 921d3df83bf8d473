#pragma once
// The thesis's three probability models (see probability_model.h for what
// each does and why; ours, "learned", is learned_model.h). Only make_model
// and tests name these classes.

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

}  // namespace acomms::telemetry
