#pragma once
// Unsigned 64-bit arithmetic that stops at the maximum instead of wrapping.
//
// Used where a bound is summed from parts that may each be "unbounded" (the
// maximum): the size in bits of a DCCL message is the sum of its fields'
// sizes, and a repeated field's is a count times an element's. A wrapped sum
// would turn "too large for any frame" into a small number, so such sums
// saturate: once any part is the maximum, so is the total. (uint64_t only:
// the callers mix narrower unsigned types, which convert without loss.)
//
// Thread-safe: constexpr pure functions.

#include <cstdint>
#include <limits>

namespace acomms::util {

// a + b, or the maximum when that would overflow.
constexpr uint64_t saturating_add(uint64_t a, uint64_t b) {
  return a > std::numeric_limits<uint64_t>::max() - b ? std::numeric_limits<uint64_t>::max() : a + b;
}

// a * b, or the maximum when that would overflow.
constexpr uint64_t saturating_mul(uint64_t a, uint64_t b) {
  if (a != 0 && b > std::numeric_limits<uint64_t>::max() / a) return std::numeric_limits<uint64_t>::max();
  return a * b;
}

}  // namespace acomms::util
