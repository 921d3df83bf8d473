// Property test: float fields quantise exactly as the reference DCCL does.
//
// The reference promotes a float field's value to double, quantises it in
// double arithmetic, stores the result back as float and compares that float
// (promoted again) with min and max (dccl-wire.md, Numbers). Rounding in
// float arithmetic instead differs on a large share of values near a
// rounding midpoint, which is where this test looks: millions of floats at
// and a few ulps around the midpoints of many field shapes, each encoded by
// NumericCore<float> and by a plain double-arithmetic oracle written from
// the spec.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "dccl/numeric.h"

namespace {

using acomms::dccl::EncodeContext;
using acomms::dccl::NumericBounds;
using acomms::dccl::NumericCore;

struct Shape {
  double min, max;
  bool has_precision;
  int precision;
  double resolution;
  bool optional;
};

// dccl-wire.md, Numbers, in double arithmetic; the quantised value is
// stored as float before the range check.
class Oracle {
 public:
  explicit Oracle(const Shape& s)
      : s_(s),
        res_(s.has_precision ? std::pow(10.0, -s.precision) : s.resolution),
        scale_(s.has_precision ? std::pow(10.0, s.precision) : 1.0 / res_) {}

  double quantize(double v) const {
    return res_ < 1 ? std::floor(v * scale_ + 0.5) / scale_ : std::floor(v / res_ + 0.5) * res_;
  }

  uint64_t wire(float x) const {
    const double w = static_cast<float>(quantize(x));
    if (w < s_.min || w > s_.max) return 0;
    const double q = w - quantize(s_.min);
    const double u = res_ < 1 ? std::floor(q * scale_ + 0.5) : std::floor(q / res_ + 0.5);
    return static_cast<uint64_t>(u) + (s_.optional ? 1 : 0);
  }

  // The old, wrong rule (all in float): used only to show that the inputs
  // reach the cases where the two differ.
  uint64_t float_wire(float x) const {
    const float s = static_cast<float>(scale_), r = static_cast<float>(res_);
    auto q = [&](float v) { return res_ < 1 ? std::floor(v * s + 0.5f) / s : std::floor(v / r + 0.5f) * r; };
    const float w = q(x);
    if (w < s_.min || w > s_.max) return 0;
    const float d = w - q(static_cast<float>(s_.min));
    const float u = res_ < 1 ? std::floor(d * s + 0.5f) : std::floor(d / r + 0.5f);
    return static_cast<uint64_t>(u) + (s_.optional ? 1 : 0);
  }

  double res() const { return res_; }

 private:
  Shape s_;
  double res_, scale_;
};

NumericCore<float> core_for(const Shape& s) {
  NumericBounds b;
  b.min = s.min;
  b.max = s.max;
  b.has_precision = s.has_precision;
  b.precision = s.precision;
  b.resolution = s.has_precision ? std::pow(10.0, -s.precision) : s.resolution;
  return NumericCore<float>(b, s.optional, "t.F.f");
}

TEST(FloatQuantisation, MatchesTheDoubleArithmeticOracleAroundEveryKindOfMidpoint) {
  const Shape shapes[] = {
      {0, 0.05, true, 2, 0, false},         // gv.Res4.f
      {0, 0.07, true, 2, 0, false},         // gv.Edge.c: a float equal to max
      {-1, 1, true, 3, 0, true},
      {-50, 50, true, 2, 0, true},
      {0, 360, true, 1, 0, false},
      {-180, 180, true, 4, 0, false},
      {0, 1, true, 6, 0, false},
      {-1000, 1000, true, 0, 0, false},
      {-1e5, 1e5, true, -2, 0, true},
      {-100, 100, false, 0, 2.5, false},
      {-1, 1, false, 0, 0.1, false},
      {-10, 10, false, 0, 0.25, true},
      {0.005, 0.995, true, 2, 0, false},    // min itself rounds up
  };
  std::mt19937_64 rng(20261123);
  uint64_t checked = 0, float_would_differ = 0;
  for (const Shape& shape : shapes) {
    const Oracle oracle(shape);
    const NumericCore<float> core = core_for(shape);
    const double steps = std::floor((shape.max - shape.min) / oracle.res());
    std::uniform_int_distribution<int64_t> pick(-2, static_cast<int64_t>(steps) + 2);
    for (int n = 0; n < 100000; ++n) {
      const double midpoint = oracle.quantize(shape.min) + (static_cast<double>(pick(rng)) + 0.5) * oracle.res();
      float x = static_cast<float>(midpoint);
      for (int i = 0; i < 3; ++i) x = std::nextafter(x, -INFINITY);
      for (int i = 0; i < 7; ++i, x = std::nextafter(x, INFINITY)) {
        const uint64_t want = oracle.wire(x);
        const uint64_t got = core.to_wire(x, EncodeContext{}, "t.F.f");
        ASSERT_EQ(got, want) << "value " << x << " (" << static_cast<double>(x) << ") min " << shape.min
                             << " max " << shape.max << " res " << oracle.res();
        ++checked;
        if (oracle.float_wire(x) != want) ++float_would_differ;
      }
    }
  }
  EXPECT_GE(checked, 9000000u);
  // The inputs do sit where float rounding goes wrong: a test that never
  // got there could not tell the two rules apart.
  EXPECT_GT(float_would_differ, checked / 50) << float_would_differ << " of " << checked;
}

TEST(FloatQuantisation, TheIssueExamples) {
  const NumericCore<float> res4 = core_for({0, 0.05, true, 2, 0, false});
  EXPECT_EQ(res4.to_wire(0.015f, EncodeContext{}, "f"), 1u);  // 0.015f is 0.01499999966: 0.01
  const NumericCore<float> edge = core_for({0, 0.07, true, 2, 0, false});
  EXPECT_EQ(edge.to_wire(0.07f, EncodeContext{}, "f"), 0u);   // 0.07f > 0.07: out of range
  EXPECT_EQ(edge.to_wire(0.06f, EncodeContext{}, "f"), 6u);
}

}  // namespace
