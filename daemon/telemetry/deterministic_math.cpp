#include "telemetry/deterministic_math.h"

#include <cmath>

namespace acomms::telemetry {

double exp_neg(double x) {
  if (!(x >= 0)) return 1;  // NaN or negative: callers pass squares
  if (x > 745) return 0;
  // x = k ln2 + r, |r| <= ln2 / 2; ln2 split so that k * kLn2High is exact.
  constexpr double kLn2High = 6.93147180369123816490e-01;
  constexpr double kLn2Low = 1.90821492927058770002e-10;
  constexpr double kInvLn2 = 1.44269504088896338700e+00;
  const double k = std::floor(x * kInvLn2 + 0.5);
  const double r = (x - k * kLn2High) - k * kLn2Low;
  // exp(-r) by Horner on the Taylor coefficients 1/n! (n = 0..13, exact
  // decimal-to-double constants); the next term, r^14/14!, is below 2^-60
  // on |r| <= 0.35.
  static constexpr double kInverseFactorial[14] = {
      1.0, 1.0, 1.0 / 2, 1.0 / 6, 1.0 / 24, 1.0 / 120, 1.0 / 720, 1.0 / 5040, 1.0 / 40320, 1.0 / 362880,
      1.0 / 3628800, 1.0 / 39916800, 1.0 / 479001600, 1.0 / 6227020800};
  double sum = kInverseFactorial[13];
  for (int n = 12; n >= 0; --n) sum = kInverseFactorial[n] - r * sum;
  return std::ldexp(sum, -static_cast<int>(k));
}

int64_t round_to_int(double x) {
  constexpr double kLimit = 4611686018427387904.0;  // 2^62
  if (!(x == x)) return 0;
  if (x >= kLimit) return int64_t{1} << 62;
  if (x <= -kLimit) return -(int64_t{1} << 62);
  return static_cast<int64_t>(x < 0 ? -std::floor(-x + 0.5) : std::floor(x + 0.5));
}

uint64_t isqrt(uint64_t n) {
  uint64_t root = 0;
  uint64_t bit = uint64_t{1} << 62;
  while (bit > n) bit >>= 2;
  while (bit != 0) {
    if (n >= root + bit) {
      n -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return root;
}

uint64_t isqrt_rounded(uint64_t n) {
  const uint64_t root = isqrt(n);
  // round up when n >= (root + 1/2)^2 = root^2 + root + 1/4, i.e. n > root^2 + root
  return n > root * root + root ? root + 1 : root;
}

}  // namespace acomms::telemetry
