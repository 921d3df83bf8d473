#pragma once
// Integer frequency tables for a Gaussian innovation model.
//
// The arithmetic coder needs integer frequencies, and both ends must build
// exactly the same ones. So the Gaussian's parameters are first quantised to
// sixteenths of a precision step (mean16, sigma16: integers), and the table
// for them is then computed from basic IEEE operations only
// (deterministic_math.h): the density is integrated over each unit bin
// [d - 1/2, d + 1/2) by Simpson's rule on 8 panels, truncated to the bounds,
// scaled to kGaussianScale and floored, plus 1 so that no in-range
// innovation has zero frequency (an unlikely one costs at most about
// log2(kGaussianScale + bins) bits, never an unencodable symbol).

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "dccl/arithmetic_coder.h"

namespace acomms::telemetry {

inline constexpr uint32_t kGaussianScale = 1u << 16;
// sigma16 bounds: sigma from 1/4 to 4096 precision steps.
inline constexpr int64_t kMinSigma16 = 4;
inline constexpr int64_t kMaxSigma16 = 16 * 4096;

// sigma = sqrt(variance) in sixteenths, rounded and clamped to the bounds.
// variance in precision steps squared.
int64_t sigma16_of_variance(double variance);

// The table for symbols S(d) = d - d_min, d in [d_min, d_max).
std::vector<uint32_t> gaussian_frequencies(int32_t d_min, int32_t d_max, int64_t mean16,
                                           int64_t sigma16);

// Tables already built, by (mean16, sigma16): the Kalman filter's variance
// settles within a few samples, so a handful of tables serve a whole track.
// References stay valid until trim() (node-based map), which models call at
// each full transmission: between two fulls at most 3 (N + 1) tables are added.
class GaussianTableCache {
 public:
  GaussianTableCache(int32_t d_min, int32_t d_max) : d_min_(d_min), d_max_(d_max) {}
  const dccl::arith::FrequencyTable& get(int64_t mean16, int64_t sigma16);
  // Forgets every table once there are more than kMaxEntries.
  void trim() {
    if (tables_.size() > kMaxEntries) tables_.clear();
  }

 private:
  static constexpr size_t kMaxEntries = 1024;
  int32_t d_min_, d_max_;
  std::unordered_map<uint64_t, dccl::arith::FrequencyTable> tables_;
};

}  // namespace acomms::telemetry
