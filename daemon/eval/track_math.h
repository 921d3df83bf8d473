#pragma once
// The arithmetic of the realistic track generator (realistic_track.h), from
// IEEE basic operations only.
//
// A generated track is a test fixture: its tests assert bits per delta on a
// fixed seed, so the same seed must give the same metres on every machine.
// glibc's sin, cos, atan2, exp and log are not correctly rounded and pick
// FMA or non-FMA code by CPU at run time, and a vehicle simulation feeds its
// own heading back into itself, so one last-bit difference could move a
// sample across a rounding boundary. Everything here is +, -, *, / and
// sqrt (correctly rounded by IEEE-754) with fixed evaluation order: Taylor
// series after exact-enough range reduction, good to about 1e-15, which is
// far below what a track needs; exactness across machines is the point.
//
// Thread-safe: pure functions; a TrackNoise is one track's state.

#include <cstdint>

#include "util/splitmix64.h"

namespace acomms::eval {

inline constexpr double kTrackPi = 3.14159265358979323846;

double track_sin(double x);
double track_cos(double x);
// The angle of (x, y) in (-pi, pi]; 0 for (0, 0).
double track_atan2(double y, double x);
// exp(x) for x <= 0 (decay factors, wave orbits): telemetry's exp_neg.
double track_exp_neg(double x);
// x wrapped into (-pi, pi].
double wrap_pi(double x);

// Standard normal deviates (Irwin-Hall: the sum of 12 uniforms minus 6;
// bounded at 6 sigma, which a track never misses) and uniforms, from one
// seeded SplitMix64.
class TrackNoise {
 public:
  explicit TrackNoise(uint64_t seed) : random_(seed) {}
  double normal();
  double uniform(double lo, double hi) { return lo + (hi - lo) * random_.uniform(); }

 private:
  util::SplitMix64 random_;
};

// A first-order Gauss-Markov process (mean 0, standard deviation sigma,
// correlation time tau_s): the shape of slowly wandering errors (a current's
// random part, a heading controller's hunting, a speed that is never quite
// the commanded one).
struct GaussMarkov {
  double sigma = 0;
  double tau_s = 1;
  double value = 0;
  double step(TrackNoise& noise, double dt_s);
};

}  // namespace acomms::eval
