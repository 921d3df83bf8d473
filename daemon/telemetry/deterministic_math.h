#pragma once
// Arithmetic that gives the same bits on every build and platform.
//
// Both ends of a telemetry stream must round the same prediction to the same
// grid point and build the same frequency table, or the receiver decodes a
// different position and every later one with it. IEEE-754 guarantees
// correctly rounded +, -, *, / and sqrt, but not exp, erf, sin or atan2
// (libm versions and vector paths differ in the last bit). So everything the
// two ends compare is built from the basic operations only (and the library
// is compiled without FMA contraction, see CMakeLists.txt).
//
// Thread-safe: pure functions.

#include <cstdint>

namespace acomms::telemetry {

// exp(-x) for x >= 0 from basic operations only (Cody-Waite reduction by
// ln 2, a degree-13 Taylor polynomial on [-ln2/2, ln2/2], exact scaling by
// 2^-k). Relative error below 1e-15; 0 beyond x = 745.
double exp_neg(double x);

// The nearest integer, halves away from zero; saturates at +-2^62.
int64_t round_to_int(double x);

// floor(sqrt(n)) exactly.
uint64_t isqrt(uint64_t n);

// round(sqrt(n)) exactly (halves cannot occur for integer n).
uint64_t isqrt_rounded(uint64_t n);

}  // namespace acomms::telemetry
