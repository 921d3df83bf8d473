#pragma once
// A vehicle's depth loop as a generated track sees it (realistic_track.h):
// a commanded depth is reached at a limited vertical rate and overshot.
//
// A torpedo AUV changes depth by pitching (15-20 degrees at 1.5 m/s: at most
// about 0.5 m/s vertically), and its pitch and depth loops respond like a
// damped second-order system: it closes on a new depth at the rate limit,
// overshoots by a metre or two, and settles after an oscillation or two. A
// yo-yo (the command flipping between two depths) turns at each end with
// that overshoot. Modelled as z'' = wn^2 (command - z) - 2 zeta wn z', with
// z' clamped to the rate limit and z >= 0 (the surface), integrated by
// semi-implicit Euler. Depth is positive down here; tracks store z = -depth.
//
// Not thread-safe: one track's state.

namespace acomms::eval {

class DepthController {
 public:
  DepthController(double natural_period_s, double damping, double max_rate_mps);
  // Advances by dt_s towards command_m; returns the new depth.
  double step(double command_m, double dt_s);
  double depth() const { return depth_; }
  double rate() const { return rate_; }

 private:
  double omega_, damping_, max_rate_;
  double depth_ = 0, rate_ = 0;
};

}  // namespace acomms::eval
