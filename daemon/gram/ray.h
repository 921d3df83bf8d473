// One ray of the fan, traced step by step with its dynamic quantities.
//
// Problem: the field is a sum over rays; each needs position, travel time,
// the spreading q and its derivative p (dynamic ray equations), the product
// of reflection coefficients, the caustic count and the bounce counts at
// every step point (spec §4.1–§4.6). Storing whole rays costs too much
// memory for steep rays in a lossless waveguide (tens of thousands of
// steps), so the tracer is an iterator: next() yields one step point at a
// time and the caller consumes the segment between two points.
// Invariants: every step lands exactly on c-linear SSP nodes, the surface
// and the bottom (so c_z jumps and reflections happen at step points);
// the slowness vector is renormalised to 1/c after each step.
// Not thread-safe (one tracer per thread); the Medium is shared read-only.
#pragma once

#include <complex>
#include <cstddef>

#include "gram/medium.h"

namespace acomms::gram {

struct RayPoint {
  double r = 0, z = 0;    // m
  double xi = 0, zeta = 0;  // slowness vector (cos θ, sin θ)/c
  double tau = 0;         // travel time, s
  double q = 0, p = 0;    // dynamic ray quantities (geometric beam: q(0) = 0)
  double c = 0;           // sound speed at the point
  double s = 0;           // arc length, m
  std::complex<double> reflection{1.0, 0.0};  // product of reflection coefficients so far
  int caustics = 0;
  int top_bounces = 0, bottom_bounces = 0;
};

class RayTracer {
 public:
  RayTracer(const Medium& medium, double launch_angle_rad);

  const RayPoint& point() const { return points_[current_]; }
  // The point before point(): after next() returned true, the start of the
  // segment it just traced (kept so callers need not copy every point).
  const RayPoint& previous() const { return points_[current_ ^ 1]; }
  // Advances one step; false when the ray has ended (box, turned back,
  // amplitude below the floor, step limit). point() is then unchanged.
  bool next();

 private:
  // Writes r, z, ξ, ζ, τ, q, p, s of the step of length h from `from` into
  // `out` (not `from`); the other fields of `out` are left to the caller.
  void integrate(const RayPoint& from, const SoundSpeedProfile::Value& at_from, double h,
                 RayPoint& out) const;
  void land_on_node(std::size_t node);
  void reflect(bool top);
  double bottom_offset(const RayPoint& at) const;  // z − bottom depth (< 0 in water)
  void update_fade();  // recomputes faded_at_s_ after the reflection product changed

  const Medium& medium_;
  // Two slots, alternating: next() writes the new point over the one before
  // the current, so a step copies nothing.
  RayPoint points_[2];
  unsigned current_ = 0;
  std::size_t layer_ = 0;
  SoundSpeedProfile::Value here_{};  // c, c_z, c_zz at point_ in layer_
  std::size_t segment_ = 0;
  std::size_t steps_ = 0;
  double faded_at_s_ = 0;  // arc length beyond which the amplitude is below the floor
  bool ended_ = false;
};

}  // namespace acomms::gram
