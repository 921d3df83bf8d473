#pragma once
// The "learned" probability model (ours; probability_model.h lists the
// others): what a vehicle's innovations look like, learned from the ones
// sent, in context.
//
// The thesis's adaptive model counts every innovation of an axis in one
// histogram from a uniform start. Real tracks are not one distribution:
// straight legs give innovations of a step or two, a turn, a yo-yo's end or
// a GPS-aided stretch at the surface a run of large ones of one sign, and
// the regime changes over the hours. So, per axis:
// - Context: the previous innovation of the axis, in one of 9 signed
//   classes (0, +-1, +-2..3, +-4..7, +-8 and beyond). A large innovation is
//   followed by another (the observer lags a turn for several samples),
//   usually of the same sign; a small one by a small one. Each context has
//   its own statistics.
// - Within a context, a Gaussian prior mixed with counts:
//     f(d) = G(mean, var)(d) + w N_d,   w = 2^13
//   where N_d counts d in this context, mean = sum d / (n + 1) (shrunk
//   towards 0) and var = (v0 + sum (d - mean)^2) / (1 + n), v0 the
//   observer's variance (the observer's Gaussian weighs one sample); G the integer
//   Gaussian table (gaussian_table.h, floor 1, scale 2^16). Before any
//   innovation it is exactly the observer's Gaussian; a count weighs 1/8
//   of the Gaussian, so after about 8 innovations in a context the counts
//   carry what is not Gaussian while the Gaussian still smooths what was
//   not seen yet (contexts are sparser than one histogram).
// - Forgetting: once 64 innovations are in a context, its statistics are
//   halved (integer division towards zero): an exponential window of the
//   last hundred or so, so the model follows a change of regime (another
//   leg's heading and speed for the fixed-speed observer, another current,
//   a glider's surface stretch) instead of averaging the whole mission.
// Worth, in bits per delta on the realistic tracks (eval/realistic_track.h,
// defaults; tests/unit/telemetry/learned_model_test.cpp shows each): the
// context 0.3-1.0, the lighter counts 0.1-0.3 (about nothing on a
// glider), forgetting 0.05-0.9 (most for the fixed-speed observer); all
// together 0.6-2.2 against the learned model of before, to 7.8-9.0 bits
// on torpedo AUV tracks and 5.4-6.3 on glider tracks.
// Integers throughout (means in sixteenths, variances in 1/256 of a
// precision step squared, the Gaussian tables from deterministic_math.h),
// so both ends build identical tables on any build.
//
// Not thread-safe: one stream's state.

#include <array>
#include <vector>

#include "telemetry/gaussian_table.h"
#include "telemetry/probability_model.h"

namespace acomms::telemetry {

class LearnedModel final : public ProbabilityModel {
 public:
  static constexpr int kContexts = 9;
  // Weight of the observer's Gaussian as the prior, in samples.
  static constexpr int64_t kObserverPrior = 1;
  // The most innovations a context holds (and the most the statistics
  // accept back); reaching it halves them.
  static constexpr int64_t kMaxContextLimit = ProbabilityModel::kForgetAfter;

  // What the stream runs is the default; the others exist so that tests
  // can show what each part is worth (the model of before: one context,
  // halving at kForgetAfter).
  struct Options {
    bool context = true;
    // Innovations a context holds before it is halved, at most
    // kMaxContextLimit.
    int64_t context_limit = 64;
    // What one counted innovation weighs against the Gaussian's 2^16.
    uint32_t count_weight = kGaussianScale / 8;
  };
  // The learned model of before (one context, counts halved only at
  // kForgetAfter, a count worth half the Gaussian).
  static Options before() { return Options{false, kMaxContextLimit, kGaussianScale / 2}; }

  LearnedModel(int32_t d_min, int32_t d_max) : LearnedModel(d_min, d_max, Options{}) {}
  LearnedModel(int32_t d_min, int32_t d_max, const Options& options);
  void reset() override;
  void trim() override { cache_.trim(); }
  const dccl::arith::FrequencyTable& table(int axis, double variance) override;
  void observe(int axis, int32_t innovation) override;
  // Per axis: the previous innovation, then per context its count, sum,
  // sum of squares and histogram.
  std::vector<int64_t> statistics() const override;
  bool restore_statistics(const std::vector<int64_t>& statistics) override;

  // The context class of an innovation, 0 .. kContexts - 1.
  static int context_of(int32_t innovation);

 private:
  struct Context {
    int64_t count = 0;
    int64_t sum = 0;
    int64_t sum_of_squares = 0;
    std::vector<uint32_t> histogram;
  };
  struct Axis {
    int32_t previous = 0;
    std::array<Context, kContexts> contexts;
  };
  int context_index(int axis) const;

  Options options_;
  GaussianTableCache cache_;
  std::array<Axis, kAxes> axes_;
  std::array<dccl::arith::FrequencyTable, kAxes> tables_;
};

}  // namespace acomms::telemetry
