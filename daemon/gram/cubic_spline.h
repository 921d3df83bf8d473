// Cubic spline with not-a-knot end conditions.
//
// Problem: BELLHOP's 'S' profiles are splines, and rays are sensitive to the
// end conditions: with not-a-knot (third derivative continuous across the
// second and second-to-last node) rays agree with BELLHOP's to < 0.1 m over
// 99 km in a Munk profile; natural ends differ by up to 75 m (spec §1.1).
// Decision: store per interval the value and the three derivatives at its
// left node; N = 2 is the line, N = 3 the parabola through the points.
// Thread-safe after construction (const evaluation only).
#pragma once

#include <cstddef>
#include <vector>

namespace acomms::gram {

class CubicSpline {
 public:
  // x strictly increasing, x.size() == y.size() >= 2 (checked by callers).
  CubicSpline(std::vector<double> x, const std::vector<double>& y);

  struct Value {
    double f, df, d2f;
  };
  // On interval `i` ([x_i, x_{i+1}]), at any x (extrapolates the cubic).
  Value evaluate(std::size_t interval, double x) const;

 private:
  std::vector<double> x_;
  // f = a + b t + c t² + d t³ with t = x − x_i, per interval.
  std::vector<double> a_, b_, c_, d_;
};

}  // namespace acomms::gram
