#include "dccl/numeric.h"

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <type_traits>

namespace acomms::dccl {
namespace {

using i128 = __int128;

constexpr double kTwo64 = 18446744073709551616.0;
constexpr double kTwo120 = 1.329227995784916e36;

i128 clamp128(double d) {
  if (d >= kTwo120) return i128{1} << 120;
  if (d <= -kTwo120) return -(i128{1} << 120);
  return static_cast<i128>(d);
}

// Rounds to a multiple of step the way the reference does for integers:
// remainder by C++'s truncating %, half up; negative values therefore
// round toward zero.
i128 quantize_int(i128 v, i128 step) {
  i128 rem = v % step;
  if (static_cast<double>(rem) >= static_cast<double>(step) / 2.0) return v - rem + step;
  return v - rem;
}

// A double -> integer conversion that is defined for every input.
template <typename T>
T clamp_to(double d) {
  const double lo = static_cast<double>(std::numeric_limits<T>::lowest());
  const double hi = std::ldexp(1.0, std::numeric_limits<T>::digits);  // max + 1
  if (!(d >= lo)) return std::numeric_limits<T>::lowest();
  if (d >= hi) return std::numeric_limits<T>::max();
  return static_cast<T>(d);
}

}  // namespace

unsigned ceil_log2(uint64_t n) {
  unsigned b = 0;
  while (b < 64 && (uint64_t{1} << b) < n) ++b;
  return b;
}

uint64_t x86_double_to_u64(double d) {
  constexpr double k63 = 9223372036854775808.0;
  constexpr uint64_t kIndefinite = uint64_t{1} << 63;
  // cvttsd2si: truncation to int64, or the "indefinite" 2^63 when that
  // does not exist (NaN, out of range).
  auto cvtt = [](double v) -> uint64_t {
    if (!(v >= -k63 && v < k63)) return kIndefinite;
    return static_cast<uint64_t>(static_cast<int64_t>(v));
  };
  // Values from 2^63 up: subtract 2^63, convert, flip the top bit back.
  if (d >= k63) return cvtt(d - k63) ^ kIndefinite;
  return cvtt(d);
}

std::string format_number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

template <typename T>
NumericCore<T>::NumericCore(const NumericBounds& b, bool optional, const std::string& path)
    : min_(b.min), max_(b.max), res_(b.resolution), optional_(optional) {
  auto fail = [&](const std::string& rule) { throw schema_error(path + ": " + rule); };
  if (!std::isfinite(min_) || !std::isfinite(max_)) fail("min and max must be finite");
  if (max_ < min_) fail("max " + format_number(max_) + " is less than min " + format_number(min_));
  if (!(res_ > 0) || !std::isfinite(res_)) fail("resolution must be a positive number");
  use_scale_ = res_ < 1;
  scale_ = b.has_precision ? std::pow(10.0, b.precision) : 1.0 / res_;
  if (!std::isfinite(scale_)) fail("precision " + std::to_string(b.precision) + " is out of range");

  // Same order of double operations as the reference: a different order
  // changes the bit count at edges such as max 0.07 with precision 2.
  double count = std::ceil((max_ - min_) / res_ + 1 + (optional ? 1 : 0));
  if (!(count <= kTwo64)) fail("range [min, max] / resolution needs more than 64 bits");
  bits_ = 0;
  while (bits_ < 64 && std::ldexp(1.0, static_cast<int>(bits_)) < count) ++bits_;
  max_u_ = bits_ >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits_) - 1;

  if constexpr (std::is_integral_v<T>) {
    int_path_ = res_ >= 1 && res_ == std::floor(res_) && res_ < 4.0e18;
    step_ = int_path_ ? static_cast<i128>(res_) : 1;
    min_i_ = clamp128(std::ceil(min_));
    max_i_ = clamp128(std::floor(max_));
    i128 tmin = clamp128(std::trunc(min_));
    qmin_i_ = int_path_ ? quantize_int(tmin, step_) : tmin;
  } else {
    if constexpr (std::is_same_v<T, float>) {
      if (std::fabs(min_) > FLT_MAX || std::fabs(max_) > FLT_MAX) fail("min/max out of range for float");
      if ((use_scale_ ? scale_ : res_) > FLT_MAX) fail("resolution out of range for float");
    }
    qmin_ = quantize(min_);
  }
}

template <typename T>
double NumericCore<T>::quantize(double x) const {
  return use_scale_ ? std::floor(x * scale_ + 0.5) / scale_ : std::floor(x / res_ + 0.5) * res_;
}

template <typename T>
uint64_t NumericCore<T>::to_wire(T x, const EncodeContext& ctx, const std::string& path) const {
  auto out_of_range = [&]() -> uint64_t {
    if (ctx.strict) {
      throw encode_error(path + ": value " + format_number(static_cast<double>(x)) +
                         " out of range [" + format_number(min_) + ", " + format_number(max_) + "]");
    }
    return 0;
  };
  const uint64_t offset = optional_ ? 1 : 0;

  if constexpr (std::is_integral_v<T>) {
    i128 v = x;
    i128 w = int_path_ ? quantize_int(v, step_) : v;
    if (w < min_i_ || w > max_i_) return out_of_range();
    // value - min in the field's own type, wrapping as the reference's does
    // on x86-64: only signed fields whose range is wider than the type's
    // positive half wrap (to negative, then sign-extended).
    const i128 diff = static_cast<T>(w - qmin_i_);
    uint64_t u;
    if (int_path_) {
      u = masked(static_cast<uint64_t>(static_cast<int64_t>(diff / step_)) + offset);
    } else {
      double d = static_cast<double>(diff);
      d = use_scale_ ? std::floor(d * scale_ + 0.5) : std::floor(d / res_ + 0.5);
      u = masked(x86_double_to_u64(d) + offset);
    }
    // The wrap can turn an optional value into "not set" (int32 max in
    // [-2^31, 2^31 - 1]): strict mode refuses to lose it.
    if (ctx.strict && optional_ && u == 0) {
      throw encode_error(path + ": value " + format_number(static_cast<double>(x)) +
                         " would arrive as not set (value - min overflows the field's type in the reference DCCL)");
    }
    return u;
  } else {
    // Quantised in double; a float field keeps the result as a float.
    const double w = static_cast<double>(static_cast<T>(quantize(static_cast<double>(x))));
    if (w < min_ || w > max_) return out_of_range();  // NaN passes, as in the reference
    if (ctx.strict && std::isnan(w)) return out_of_range();
    const double d = use_scale_ ? std::floor((w - qmin_) * scale_ + 0.5) : std::floor((w - qmin_) / res_ + 0.5);
    return masked(x86_double_to_u64(d) + offset);
  }
}

template <typename T>
std::optional<T> NumericCore<T>::from_wire(uint64_t u) const {
  if (optional_) {
    if (u == 0) return std::nullopt;
    --u;
  }
  if constexpr (std::is_integral_v<T>) {
    if (int_path_) {
      i128 v = qmin_i_ + static_cast<i128>(u) * step_;
      return static_cast<T>(v);  // modular, as C++20 defines it
    }
    double d = static_cast<double>(qmin_i_) +
               (use_scale_ ? static_cast<double>(u) / scale_ : static_cast<double>(u) * res_);
    return clamp_to<T>(std::floor(d + 0.5));
  } else {
    double d = qmin_ + (use_scale_ ? static_cast<double>(u) / scale_ : static_cast<double>(u) * res_);
    // With min 0, u / scale (or u * res) is already on the grid: quantising
    // gives it back exactly (|d * scale - u| is a few ulps of u, far below
    // 0.5, for u < 2^51), so the hot decode path skips it.
    if (qmin_ != 0 || u >= (uint64_t{1} << 51)) d = quantize(d);
    if constexpr (std::is_same_v<T, float>) {
      if (d > FLT_MAX) d = FLT_MAX;
      if (d < -FLT_MAX) d = -FLT_MAX;
    }
    return static_cast<T>(d);
  }
}

template class NumericCore<int32_t>;
template class NumericCore<int64_t>;
template class NumericCore<uint32_t>;
template class NumericCore<uint64_t>;
template class NumericCore<float>;
template class NumericCore<double>;

}  // namespace acomms::dccl
