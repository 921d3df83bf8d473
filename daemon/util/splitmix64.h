#pragma once
// SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014): the random numbers of the offline evaluations.
//
// The evaluations promise "same seed, same output" on any machine. The
// standard engines are fully specified but the standard distributions are
// not (std::uniform_real_distribution differs between libraries), so the
// generator and the mapping to [0, 1) are written out here, once.
//
// Invariant: the output sequence for a seed never changes. The evaluations'
// published numbers and their tests depend on it (see
// tests/unit/util/splitmix64_test.cpp for the reference values).
//
// Not thread-safe: a generator is one sequence's state; give each thread its
// own (same seed, same numbers).

#include <cstdint>

namespace acomms::util {

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}

  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  // Uniform on [0, 1): the top 53 bits of next(), so every value is an
  // exact double.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  // In [0, n) for n >= 1, by the remainder of next(): slightly biased
  // towards small values unless n divides 2^64 (at most n / 2^64, far below
  // what an evaluation can see). Kept so, because the evaluations' results
  // depend on this exact mapping.
  uint64_t below(uint64_t n) { return next() % n; }

 private:
  uint64_t state_;
};

}  // namespace acomms::util
