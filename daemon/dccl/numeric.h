// DCCL's bounded-number rule, shared by integer, floating-point, enum and
// time fields.
//
//   res  = precision set ? 10^-precision : resolution
//   bits = ceil_log2(ceil((max - min) / res + 1 + (optional ? 1 : 0)))
//   encode: w = quantize(x); out of [min, max] -> 0 (or an error when strict)
//           else u = round((w - quantize(min)) / res), +1 when optional
//
// The arithmetic deliberately follows the reference encoder, which a fielded
// vehicle runs (dccl-wire.md, Numbers):
//  - floating values quantise in double; a float field stores the result
//    back as float and compares that float, promoted, with min and max (so a
//    float equal to max can fall out of range, and 0.015f at precision 2 is
//    0.01: 0.015f is 0.01499999966);
//  - round(x) = floor(x + 0.5) on the binary value; integers with res > 1
//    round with C++'s truncating % (positives half up, negatives toward
//    zero);
//  - where the reference's result comes from undefined behaviour, this
//    reproduces what it does on x86-64 Linux: a NaN passes the range check
//    and its wire value is the x86 "integer indefinite" 2^63 (+1 when
//    optional) cut to the field's bits, and an integer field's value - min
//    wraps in the field's own type (int32 ranges wider than 2^31 give
//    sign-extended wire bits). Strict mode refuses NaN instead.
// Everything that depends only on the options is computed once in the
// constructor.
//
// Thread-safe once built: a NumericCore is only read while coding, so the
// codecs holding one may encode and decode concurrently.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "dccl/field_codec.h"

namespace acomms::dccl {

struct NumericBounds {
  double min = 0;
  double max = 0;
  double resolution = 1;
  bool has_precision = false;  // resolution came from precision
  int32_t precision = 0;
};

template <typename T>
class NumericCore {
 public:
  NumericCore() = default;
  // Throws schema_error("<path>: ...") for bounds that cannot be encoded.
  NumericCore(const NumericBounds& bounds, bool optional, const std::string& path);

  unsigned bits() const { return bits_; }
  double resolution() const { return res_; }

  // The wire value for x (0 when out of range, unless ctx.strict: then it
  // throws encode_error naming `path`).
  uint64_t to_wire(T x, const EncodeContext& ctx, const std::string& path) const;
  // The value for wire value u; nullopt for the "not set" value.
  std::optional<T> from_wire(uint64_t u) const;

 private:
  double quantize(double x) const;
  uint64_t masked(uint64_t u) const { return u & max_u_; }

  double min_ = 0, max_ = 0, res_ = 1;
  bool optional_ = false;
  bool use_scale_ = false;  // res < 1: quantise as floor(x * scale + 0.5) / scale
  double scale_ = 1;        // 1 / res (10^precision when precision is set)
  bool int_path_ = false;   // integer field with integral res >= 1
  __int128 step_ = 1;       // res as an integer (int_path_)
  __int128 min_i_ = 0, max_i_ = 0, qmin_i_ = 0;  // integer fields
  double qmin_ = 0;                              // floating fields
  unsigned bits_ = 0;
  uint64_t max_u_ = 0;
};

// Smallest b with 2^b >= n (0 for n <= 1).
unsigned ceil_log2(uint64_t n);

// double -> uint64_t as g++ compiles it on x86-64 (cvttsd2si): defined for
// every input, and what the reference's undefined conversions give there
// (NaN and values out of range -> 2^63, negatives -> two's complement).
uint64_t x86_double_to_u64(double d);

// Shortest round-trip-ish text of a number for error messages ("0.07", "101").
std::string format_number(double v);

extern template class NumericCore<int32_t>;
extern template class NumericCore<int64_t>;
extern template class NumericCore<uint32_t>;
extern template class NumericCore<uint64_t>;
extern template class NumericCore<float>;
extern template class NumericCore<double>;

}  // namespace acomms::dccl
