#include "telemetry/learned_model.h"

#include <algorithm>
#include <cassert>

#include "telemetry/deterministic_math.h"

namespace acomms::telemetry {
namespace {

// a / b rounded to nearest (halves up), b > 0, exact for negative a too.
int64_t divide_rounded(int64_t a, int64_t b) {
  const int64_t n = 2 * a + b, d = 2 * b;
  return n >= 0 ? n / d : -((-n + d - 1) / d);
}

struct Moments {
  int64_t mean16 = 0;
  int64_t var256 = 0;
};

std::vector<uint32_t> ones(int32_t d_min, int32_t d_max) {
  return std::vector<uint32_t>(static_cast<size_t>(d_max - d_min), 1);
}

// Mean (sixteenths) and variance (1/256) of count innovations with sum and
// sum_of_squares, shrunk towards prior with the weight of `weight` samples:
//   mean = (sum + w prior.mean) / (count + w)
//   var  = (w prior.var + sum (d - mean)^2) / (w + count)
Moments shrink(int64_t count, int64_t sum, int64_t sum_of_squares, Moments prior, int64_t weight) {
  Moments out;
  out.mean16 = divide_rounded(16 * sum + weight * prior.mean16, count + weight);
  // 256 sum (d - mean)^2 = 256 sum d^2 - 32 mean16 sum d + count mean16^2
  const int64_t spread256 =
      std::max<int64_t>(0, 256 * sum_of_squares - 32 * out.mean16 * sum + count * out.mean16 * out.mean16);
  out.var256 = divide_rounded(weight * prior.var256 + spread256, weight + count);
  return out;
}

}  // namespace

int LearnedModel::context_of(int32_t d) {
  const int32_t magnitude = d < 0 ? -d : d;
  const int level = magnitude == 0 ? 0 : magnitude == 1 ? 1 : magnitude <= 3 ? 2 : magnitude <= 7 ? 3 : 4;
  return 4 + (d < 0 ? -level : level);
}

int LearnedModel::context_index(int axis) const {
  // Without context every innovation falls in the class of 0.
  return options_.context ? context_of(axes_[axis].previous) : context_of(0);
}

LearnedModel::LearnedModel(int32_t d_min, int32_t d_max, const Options& options)
    : ProbabilityModel(d_min, d_max),
      options_(options),
      cache_(d_min, d_max),
      tables_{dccl::arith::FrequencyTable(ones(d_min, d_max)), dccl::arith::FrequencyTable(ones(d_min, d_max)),
              dccl::arith::FrequencyTable(ones(d_min, d_max))} {
  reset();
}

void LearnedModel::reset() {
  for (Axis& axis : axes_) {
    axis.previous = 0;
    for (Context& context : axis.contexts)
      context = Context{0, 0, 0, std::vector<uint32_t>(static_cast<size_t>(d_max_ - d_min_), 0)};
  }
}

const dccl::arith::FrequencyTable& LearnedModel::table(int index, double variance) {
  const Context& c = axes_[index].contexts[context_index(index)];
  const int64_t prior_sigma16 = sigma16_of_variance(variance);
  const Moments prior{0, prior_sigma16 * prior_sigma16};
  const Moments moments = shrink(c.count, c.sum, c.sum_of_squares, prior, kObserverPrior);
  const int64_t mean16 = moments.mean16;
  const int64_t var256 = moments.var256;
  const int64_t sigma16 =
      std::clamp(static_cast<int64_t>(isqrt_rounded(static_cast<uint64_t>(var256))), kMinSigma16, kMaxSigma16);
  const dccl::arith::FrequencyTable& gaussian = cache_.get(mean16, sigma16);
  std::vector<uint32_t> frequencies(c.histogram.size());
  for (size_t s = 0; s < frequencies.size(); ++s)
    frequencies[s] = static_cast<uint32_t>(gaussian.frequency(s)) + options_.count_weight * c.histogram[s];
  tables_[index] = dccl::arith::FrequencyTable(frequencies);
  assert(tables_[index].total() <= dccl::arith::kMaxTotalFrequency);
  return tables_[index];
}

void LearnedModel::observe(int index, int32_t innovation) {
  Axis& axis = axes_[index];
  Context& c = axis.contexts[context_index(index)];
  axis.previous = innovation;
  ++c.count;
  c.sum += innovation;
  c.sum_of_squares += int64_t{innovation} * innovation;
  ++c.histogram[symbol_of(innovation)];
  if (c.count >= options_.context_limit) {
    // Integer halving (towards zero), the same on both ends; the spread
    // stays non-negative (table() clamps it at 0).
    c.count /= 2;
    c.sum /= 2;
    c.sum_of_squares /= 2;
    for (uint32_t& n : c.histogram) n /= 2;
  }
}

std::vector<int64_t> LearnedModel::statistics() const {
  std::vector<int64_t> out;
  for (const Axis& axis : axes_) {
    out.push_back(axis.previous);
    for (const Context& c : axis.contexts) {
      out.insert(out.end(), {c.count, c.sum, c.sum_of_squares});
      for (uint32_t n : c.histogram) out.push_back(n);
    }
  }
  return out;
}

bool LearnedModel::restore_statistics(const std::vector<int64_t>& statistics) {
  const size_t bins = static_cast<size_t>(d_max_ - d_min_);
  const size_t per_context = 3 + bins, per_axis = 1 + kContexts * per_context;
  if (statistics.size() != kAxes * per_axis) return false;
  // What count innovations within the bounds can sum to: keeps table()'s
  // integer arithmetic within range for any stored bytes.
  const __int128 bound = std::max<int64_t>(-int64_t{d_min_}, d_max_);
  for (int a = 0; a < kAxes; ++a) {
    const int64_t* axis = &statistics[a * per_axis];
    if (axis[0] < d_min_ || axis[0] >= d_max_) return false;
    for (int k = 0; k < kContexts; ++k) {
      const int64_t* v = axis + 1 + k * per_context;
      if (v[0] < 0 || v[0] >= options_.context_limit || v[1] < -v[0] * bound || v[1] > v[0] * bound || v[2] < 0 ||
          v[2] > v[0] * bound * bound)
        return false;
      int64_t sum = 0;
      for (size_t s = 0; s < bins; ++s) {
        if (v[3 + s] < 0 || v[3 + s] >= options_.context_limit) return false;
        sum += v[3 + s];
      }
      if (sum >= options_.context_limit) return false;
    }
  }
  for (int a = 0; a < kAxes; ++a) {
    const int64_t* axis = &statistics[a * per_axis];
    axes_[a].previous = static_cast<int32_t>(axis[0]);
    for (int k = 0; k < kContexts; ++k) {
      const int64_t* v = axis + 1 + k * per_context;
      Context& c = axes_[a].contexts[k];
      c.count = v[0];
      c.sum = v[1];
      c.sum_of_squares = v[2];
      for (size_t s = 0; s < bins; ++s) c.histogram[s] = static_cast<uint32_t>(v[3 + s]);
    }
  }
  return true;
}

}  // namespace acomms::telemetry
