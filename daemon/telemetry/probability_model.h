#pragma once
// Probability models of the innovation dy in [d_min, d_max) (Schneider 2013,
// section 3.4): the integer frequency table the arithmetic coder codes one
// axis's innovation with.
//
// Symbol layout: S(d) = d - d_min, one symbol per in-range innovation and
// nothing else. The thesis's out-of-range and end-of-file symbols are not
// needed: each delta is its own codeword (the coder's exact end delimits it)
// and an out-of-range innovation makes the sender send a full transmission
// instead. Models adapt only to what was sent, after each encode and each
// decode alike. What they learned carries across full transmissions (a full
// re-anchors the position, it is no reason to forget the statistics): they
// forget it only at a fresh start (reset), which a full announces when
// either end lost its state (stream_predictor.h). So that counts never
// overflow the coder's 30-bit totals on a track of days, each axis's
// statistics are halved (integer division, the same on both ends) once
// kForgetAfter innovations are in them: old behaviour slowly gives way.
//
// Models (make_model):
//   uniform   every innovation alike (eq. 3.24): log2(101) ~ 6.66 bits/axis
//   gaussian  zero mean, the observer's variance: (s tau)^2 for fixed speed
//             (eq. 3.26-3.27), the diagonal of P- for the Kalman filter
//   adaptive  (N_d + 1) / (m + bins) over the m innovations sent since the
//             fresh start (eq. 3.28-3.29): starts uniform
//   learned   ours (learned_model.h): per axis, in the context of the
//             previous innovation's class, a Gaussian whose mean and
//             variance are learned (starting from the observer's) mixed
//             with counts; each context forgets by halving

#include <cstdint>
#include <memory>
#include <vector>

#include "dccl/arithmetic_coder.h"
#include "telemetry/telemetry_config.h"

namespace acomms::telemetry {

class ProbabilityModel {
 public:
  ProbabilityModel(int32_t d_min, int32_t d_max) : d_min_(d_min), d_max_(d_max) {}
  virtual ~ProbabilityModel() = default;

  // Innovations per axis after which the statistics are halved.
  static constexpr int64_t kForgetAfter = 1 << 14;

  // Forgets everything learned (at a fresh start).
  virtual void reset() = 0;
  // What the model learned, as integers (empty for a model that learns
  // nothing), and back: the stream's durable state keeps them
  // (stream_history.h). restore_statistics is false, and changes nothing,
  // for values this model could not have produced.
  virtual std::vector<int64_t> statistics() const { return {}; }
  virtual bool restore_statistics(const std::vector<int64_t>& statistics) { return statistics.empty(); }
  // Lets go of cached tables (at each full, when no table is in use): the
  // cache must not grow with the track. Changes no table's content.
  virtual void trim() {}
  // The table for axis's next innovation; variance is the observer's, in
  // precision steps squared. Valid until the next table() or observe() for
  // that axis.
  virtual const dccl::arith::FrequencyTable& table(int axis, double variance) = 0;
  // The innovation that was sent for axis (d_min <= innovation < d_max).
  virtual void observe(int axis, int32_t innovation) = 0;

  int32_t d_min() const { return d_min_; }
  int32_t d_max() const { return d_max_; }
  size_t symbol_of(int32_t innovation) const { return static_cast<size_t>(innovation - d_min_); }
  int32_t innovation_of(size_t symbol) const { return d_min_ + static_cast<int32_t>(symbol); }

 protected:
  int32_t d_min_, d_max_;
};

std::unique_ptr<ProbabilityModel> make_model(const TelemetryConfig& config);

}  // namespace acomms::telemetry
