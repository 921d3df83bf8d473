#include "eval/track_math.h"

#include <cmath>

#include "telemetry/deterministic_math.h"

namespace acomms::eval {
namespace {

// sin on [-pi/2, pi/2] by its Taylor series to x^23 (the next term is below
// 1e-18 there).
double sin_reduced(double x) {
  const double x2 = x * x;
  double term = x, sum = x;
  for (int n = 1; n <= 11; ++n) {
    term = -term * x2 / static_cast<double>((2 * n) * (2 * n + 1));
    sum += term;
  }
  return sum;
}

// atan on [-0.21, 0.21] by its series to x^31.
double atan_reduced(double t) {
  const double t2 = t * t;
  double power = t, sum = t;
  for (int n = 1; n <= 15; ++n) {
    power = -power * t2;
    sum += power / static_cast<double>(2 * n + 1);
  }
  return sum;
}

}  // namespace

double wrap_pi(double x) {
  const double turns = std::floor((x + kTrackPi) / (2 * kTrackPi));
  double r = x - turns * (2 * kTrackPi);
  if (r <= -kTrackPi) r += 2 * kTrackPi;
  if (r > kTrackPi) r -= 2 * kTrackPi;
  return r;
}

double track_sin(double x) {
  double r = wrap_pi(x);
  if (r > kTrackPi / 2) r = kTrackPi - r;
  if (r < -kTrackPi / 2) r = -kTrackPi - r;
  return sin_reduced(r);
}

double track_cos(double x) { return track_sin(x + kTrackPi / 2); }

double track_atan2(double y, double x) {
  if (x == 0 && y == 0) return 0;
  // atan of the smaller over the larger magnitude, then the octant.
  const bool steep = std::fabs(y) > std::fabs(x);
  double t = steep ? x / y : y / x;  // |t| <= 1
  // atan(t) = 2 atan(t / (1 + sqrt(1 + t^2))), twice: |t| <= tan(pi/16).
  double scale = 1;
  for (int i = 0; i < 2; ++i) {
    t = t / (1 + std::sqrt(1 + t * t));
    scale *= 2;
  }
  double a = scale * atan_reduced(t);
  if (steep) a = (y > 0 ? kTrackPi / 2 : -kTrackPi / 2) - a;
  if (x < 0 && !steep) a += y >= 0 ? kTrackPi : -kTrackPi;
  return wrap_pi(a);
}

double track_exp_neg(double x) { return telemetry::exp_neg(-x); }

double TrackNoise::normal() {
  double sum = 0;
  for (int i = 0; i < 12; ++i) sum += random_.uniform();
  return sum - 6;
}

double GaussMarkov::step(TrackNoise& noise, double dt_s) {
  const double a = track_exp_neg(-dt_s / tau_s);
  value = a * value + sigma * std::sqrt(1 - a * a) * noise.normal();
  return value;
}

}  // namespace acomms::eval
