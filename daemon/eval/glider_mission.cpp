// A glider's mission as its dead-reckoned navigation log records it: see
// realistic_track.h for every effect, its magnitude and why.

#include <algorithm>
#include <cmath>

#include "eval/mission_plan.h"
#include "eval/navigation_error.h"
#include "eval/ocean_current.h"
#include "eval/realistic_track.h"
#include "eval/surface_waves.h"

namespace acomms::eval {
namespace {

constexpr double kDegree = kTrackPi / 180;
constexpr double kHorizontalMps = 0.3;
constexpr double kVerticalMps = 0.15;
constexpr double kInflectionS = 40;
constexpr double kTurnRateRadS = 3 * kDegree;
constexpr double kLogEveryS = 4;

// The sawtooth: vertical speed (positive down) with 40 s inflections in
// which it reverses along a half cosine.
class Sawtooth {
 public:
  explicit Sawtooth(TrackNoise& noise) { new_dive(noise); }
  // Advances by dt_s; returns the vertical speed now. Counts dives.
  // surfacing: the climb goes on to the surface instead of turning.
  double step(TrackNoise& noise, double depth_m, double dt_s, bool surfacing) {
    if (inflecting_s_ > 0) {
      inflecting_s_ -= dt_s;
      const double progress = std::clamp(1 - inflecting_s_ / kInflectionS, 0.0, 1.0);
      const double sign = down_ ? 1 : -1;  // the direction it turns to
      return -sign * kVerticalMps * track_cos(kTrackPi * progress);
    }
    if (down_ && depth_m >= bottom_m_) turn(false);
    if (!down_ && depth_m <= top_m_ && !surfacing) {
      turn(true);
      ++dives_;
      new_dive(noise);
    }
    return (down_ ? 1 : -1) * kVerticalMps;
  }
  bool inflecting() const { return inflecting_s_ > 0; }
  bool climbing() const { return !down_ && inflecting_s_ <= 0; }
  int dives() const { return dives_; }
  void start_at_surface(TrackNoise& noise) {
    down_ = true;
    inflecting_s_ = 0;
    new_dive(noise);
  }

 private:
  void turn(bool down) {
    down_ = down;
    inflecting_s_ = kInflectionS;
  }
  void new_dive(TrackNoise& noise) {
    bottom_m_ = noise.uniform(80, 200);
    top_m_ = noise.uniform(3, 8);
  }
  bool down_ = true;
  double inflecting_s_ = 0, bottom_m_ = 0, top_m_ = 0;
  int dives_ = 0;
};

}  // namespace

std::vector<telemetry::Fix> glider_mission(uint64_t seed, double duration_s) {
  TrackNoise noise(seed);
  OceanCurrent current(OceanCurrentParams{0.1, 0.4, 0.08, 4 * 3600}, noise);
  MissionPlan plan(2000, 8000, 8000, noise);
  Sawtooth sawtooth(noise);
  SurfaceWaves waves(noise);
  NavigationErrorParams nav_params;
  nav_params.scale_sigma = 0.05;
  nav_params.heading_bias_sigma_rad = 1 * kDegree;
  nav_params.random_sigma_mps = 0.005;
  nav_params.random_tau_s = 1800;
  nav_params.gps_sigma_m = 3;
  nav_params.gps_wander_sigma_m = 3;
  nav_params.gps_wander_tau_s = 60;
  NavigationError navigation(nav_params);
  GaussMarkov speed_wander{0.02, 300}, heading_hunting{4 * kDegree, 90}, depth_noise{0.1, 20};
  constexpr double dt = 1;

  double x = 0, y = 0, depth = 0;
  double heading = track_atan2(plan.waypoint()[1], plan.waypoint()[0]);
  bool surface = true;
  double surface_left_s = noise.uniform(600, 1200), fix_in_s = 0;
  int surface_after_dives = 0;  // set when it dives
  std::array<double, 2> estimated_current = current.step(noise, 0, 0);
  navigation.first_gps_fix(noise);
  std::vector<telemetry::Fix> fixes;
  double next_log_s = 0;
  for (double t = 0; t <= duration_s; t += dt) {
    const std::array<double, 2> c = current.step(noise, t, dt);
    std::array<double, 2> v = c;  // at the surface: drifting
    if (surface) {
      if (fix_in_s > 0) {
        fix_in_s -= dt;
        if (fix_in_s <= 0) navigation.first_gps_fix(noise);
      } else {
        navigation.gps_fix(noise, dt);
      }
      surface_left_s -= dt;
      if (surface_left_s <= 0 && fix_in_s <= 0) {
        // What the dive just ended tells: the depth-averaged current.
        estimated_current = {c[0] + 0.02 * noise.normal(), c[1] + 0.02 * noise.normal()};
        surface = false;
        navigation.start_dive(noise);
        sawtooth.start_at_surface(noise);
        surface_after_dives = sawtooth.dives() + 3 + static_cast<int>(noise.uniform(0, 3));
      }
    } else {
      const std::array<double, 2> e = navigation.error();
      if (std::hypot(plan.waypoint()[0] - (x + e[0]), plan.waypoint()[1] - (y + e[1])) < 100) plan.next(noise);
      const double want = track_atan2(plan.waypoint()[1] - (y + e[1]), plan.waypoint()[0] - (x + e[0]));
      heading = wrap_pi(heading + std::clamp(0.3 * wrap_pi(want - heading), -kTurnRateRadS * dt, kTurnRateRadS * dt));
      const double actual = heading + heading_hunting.step(noise, dt);
      const bool surfacing = sawtooth.dives() + 1 >= surface_after_dives;
      const double w = sawtooth.step(noise, depth, dt, surfacing);
      depth = std::max(0.0, depth + w * dt);
      // The glide: horizontal speed in proportion to the vertical.
      const double speed = (kHorizontalMps + speed_wander.step(noise, dt)) * std::fabs(w) / kVerticalMps;
      const std::array<double, 2> through_water{speed * track_cos(actual), speed * track_sin(actual)};
      v = {through_water[0] + c[0], through_water[1] + c[1]};
      // Dead reckoning knows the flight and the estimated current, not the current.
      navigation.dead_reckon(noise, through_water,
                             {estimated_current[0] - c[0], estimated_current[1] - c[1]}, dt);
      if (surfacing && sawtooth.climbing() && depth <= 0.3) {
        surface = true;
        depth = 0;
        surface_left_s = noise.uniform(600, 1200);
        fix_in_s = noise.uniform(60, 90);
      }
    }
    x += v[0] * dt;
    y += v[1] * dt;
    const std::array<double, 3> orbit = waves.displacement(t, depth);
    const double noisy_depth = std::max(0.0, depth + orbit[2] + depth_noise.step(noise, dt));
    if (t >= next_log_s) {
      // Dead reckoning underwater does not see the wave orbits (no DVL);
      // the GPS at the surface does.
      const std::array<double, 2> logged = navigation.error();
      const double ride = surface ? 1 : 0;
      fixes.push_back(
          telemetry::Fix{t, {x + ride * orbit[0] + logged[0], y + ride * orbit[1] + logged[1], -noisy_depth}});
      next_log_s = t + kLogEveryS;
    }
  }
  return fixes;
}

}  // namespace acomms::eval
