// Not-a-knot cubic spline: shared/spec/gram.md §1.1.
#include "gram/cubic_spline.h"

namespace acomms::gram {
namespace {

// Second derivatives M_i at the nodes. Not-a-knot at the left end reads
// h1 M0 − (h0 + h1) M1 + h0 M2 = 0 (and mirrored at the right); M0 and
// M_{n−1} are eliminated so the interior system stays tridiagonal.
std::vector<double> second_derivatives(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  std::vector<double> m(n, 0.0);
  if (n < 3) return m;
  std::vector<double> h(n - 1), slope(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = x[i + 1] - x[i];
    slope[i] = (y[i + 1] - y[i]) / h[i];
  }
  if (n == 3) {  // the parabola: constant second derivative
    const double c = 2.0 * (slope[1] - slope[0]) / (h[0] + h[1]);
    return {c, c, c};
  }
  // Unknowns M1..M_{n−2}: h_{i−1} M_{i−1} + 2(h_{i−1}+h_i) M_i + h_i M_{i+1} = 6(s_i − s_{i−1}).
  const std::size_t k = n - 2;
  std::vector<double> lower(k, 0.0), diag(k, 0.0), upper(k, 0.0), rhs(k, 0.0);
  for (std::size_t j = 0; j < k; ++j) {
    const std::size_t i = j + 1;
    lower[j] = h[i - 1];
    diag[j] = 2.0 * (h[i - 1] + h[i]);
    upper[j] = h[i];
    rhs[j] = 6.0 * (slope[i] - slope[i - 1]);
  }
  // M0 = ((h0 + h1) M1 − h0 M2) / h1
  diag[0] += h[0] * (h[0] + h[1]) / h[1];
  upper[0] -= h[0] * h[0] / h[1];
  // M_{n−1} = ((h_{n−2} + h_{n−3}) M_{n−2} − h_{n−2} M_{n−3}) / h_{n−3}
  const double hl = h[n - 2], hp = h[n - 3];
  diag[k - 1] += hl * (hl + hp) / hp;
  lower[k - 1] -= hl * hl / hp;
  // Thomas algorithm (the system is diagonally dominant enough for splines).
  for (std::size_t j = 1; j < k; ++j) {
    const double w = lower[j] / diag[j - 1];
    diag[j] -= w * upper[j - 1];
    rhs[j] -= w * rhs[j - 1];
  }
  std::vector<double> inner(k);
  inner[k - 1] = rhs[k - 1] / diag[k - 1];
  for (std::size_t j = k - 1; j-- > 0;) inner[j] = (rhs[j] - upper[j] * inner[j + 1]) / diag[j];
  for (std::size_t j = 0; j < k; ++j) m[j + 1] = inner[j];
  m[0] = ((h[0] + h[1]) * m[1] - h[0] * m[2]) / h[1];
  m[n - 1] = ((hl + hp) * m[n - 2] - hl * m[n - 3]) / hp;
  return m;
}

}  // namespace

CubicSpline::CubicSpline(std::vector<double> x, const std::vector<double>& y) : x_(std::move(x)) {
  const std::vector<double> m = second_derivatives(x_, y);
  const std::size_t n = x_.size();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double h = x_[i + 1] - x_[i];
    a_.push_back(y[i]);
    b_.push_back((y[i + 1] - y[i]) / h - h * (2.0 * m[i] + m[i + 1]) / 6.0);
    c_.push_back(m[i] / 2.0);
    d_.push_back((m[i + 1] - m[i]) / (6.0 * h));
  }
}

CubicSpline::Value CubicSpline::evaluate(std::size_t i, double x) const {
  const double t = x - x_[i];
  return {a_[i] + t * (b_[i] + t * (c_[i] + t * d_[i])), b_[i] + t * (2.0 * c_[i] + 3.0 * t * d_[i]),
          2.0 * c_[i] + 6.0 * t * d_[i]};
}

}  // namespace acomms::gram
