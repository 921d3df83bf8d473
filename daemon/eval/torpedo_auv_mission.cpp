// A torpedo AUV's mission as its navigation log records it: see
// realistic_track.h for every effect, its magnitude and why.

#include <algorithm>
#include <cmath>

#include "eval/depth_controller.h"
#include "eval/mission_plan.h"
#include "eval/navigation_error.h"
#include "eval/ocean_current.h"
#include "eval/realistic_track.h"
#include "eval/surface_waves.h"

namespace acomms::eval {
namespace {

constexpr double kDegree = kTrackPi / 180;
constexpr double kSpeedMinMps = 1.2, kSpeedMaxMps = 2.0;
constexpr double kSurfaceSpeedMps = 0.5;
constexpr double kTurnRateRadS = 6 * kDegree;
constexpr double kArrivalM = 25;

// The depth the mission asks for: holding a depth or a yo-yo, in segments
// of 10-40 min.
class DepthPlan {
 public:
  explicit DepthPlan(TrackNoise& noise) { next_segment(noise, 0); }
  double command(TrackNoise& noise, double t_s, double depth_m) {
    if (t_s >= segment_end_s_) next_segment(noise, t_s);
    if (!yoyo_) return hold_m_;
    // The yo-yo turns when the vehicle comes within a metre of the end it
    // heads for; the depth loop's overshoot carries it past.
    if (down_ && depth_m >= bottom_m_ - 1) down_ = false;
    if (!down_ && depth_m <= top_m_ + 1) down_ = true;
    return down_ ? bottom_m_ : top_m_;
  }

 private:
  void next_segment(TrackNoise& noise, double t_s) {
    segment_end_s_ = t_s + noise.uniform(600, 2400);
    yoyo_ = noise.uniform(0, 1) < 0.5;
    hold_m_ = noise.uniform(8, 60);
    top_m_ = noise.uniform(5, 15);
    bottom_m_ = noise.uniform(30, 70);
  }
  double segment_end_s_ = 0;
  bool yoyo_ = false, down_ = true;
  double hold_m_ = 0, top_m_ = 0, bottom_m_ = 0;
};

}  // namespace

std::vector<telemetry::Fix> torpedo_auv_mission(uint64_t seed, double duration_s) {
  TrackNoise noise(seed);
  OceanCurrent current(OceanCurrentParams{0.2, 0.4, 0.05, 3 * 3600}, noise);
  MissionPlan plan(300, 2500, 8000, noise);
  DepthPlan depth_plan(noise);
  double commanded_mps = noise.uniform(kSpeedMinMps, kSpeedMaxMps);
  DepthController depth(60, 0.5, kSpeedMinMps * track_sin(20 * kDegree));
  SurfaceWaves waves(noise);
  NavigationError navigation(NavigationErrorParams{});
  GaussMarkov speed_wander{0.03, 60}, heading_hunting{1.5 * kDegree, 20}, depth_wander{0.1, 10};
  constexpr double dt = 1;

  double x = 0, y = 0;
  const std::array<double, 2> first = plan.waypoint();
  double heading = track_atan2(first[1], first[0]);
  enum class Phase { kSubmerged, kAscending, kSurface } phase = Phase::kSurface;
  double surface_left_s = noise.uniform(60, 180), fix_in_s = 0;  // starts with a fix
  double surface_at_s = 0;
  navigation.first_gps_fix(noise);
  std::vector<telemetry::Fix> fixes;
  for (double t = 0; t <= duration_s; t += dt) {
    const std::array<double, 2> c = current.step(noise, t, dt);
    // Steer for the waypoint by the vehicle's own estimate of where it is.
    const std::array<double, 2> e = navigation.error();
    if (std::hypot(plan.waypoint()[0] - (x + e[0]), plan.waypoint()[1] - (y + e[1])) < kArrivalM) {
      plan.next(noise);
      commanded_mps = noise.uniform(kSpeedMinMps, kSpeedMaxMps);
    }
    const double want = track_atan2(plan.waypoint()[1] - (y + e[1]), plan.waypoint()[0] - (x + e[0]));
    heading = wrap_pi(heading + std::clamp(0.5 * wrap_pi(want - heading), -kTurnRateRadS * dt, kTurnRateRadS * dt));
    const double actual = heading + heading_hunting.step(noise, dt);
    const double through_water = (phase == Phase::kSurface ? kSurfaceSpeedMps : commanded_mps) + speed_wander.step(noise, dt);
    // Pitched to climb or dive, less of it is horizontal.
    const double climb = std::min(std::fabs(depth.rate()) / through_water, 0.9);
    const double speed = through_water * std::sqrt(1 - climb * climb);
    const std::array<double, 2> v{speed * track_cos(actual) + c[0], speed * track_sin(actual) + c[1]};
    x += v[0] * dt;
    y += v[1] * dt;

    double command = 0;
    switch (phase) {
      case Phase::kSubmerged:
        navigation.dead_reckon(noise, v, {0, 0}, dt);
        command = depth_plan.command(noise, t, depth.depth());
        if (t >= surface_at_s) phase = Phase::kAscending;
        break;
      case Phase::kAscending:
        navigation.dead_reckon(noise, v, {0, 0}, dt);
        if (depth.depth() < 0.3) {
          phase = Phase::kSurface;
          surface_left_s = noise.uniform(60, 180);
          fix_in_s = noise.uniform(15, 45);
        }
        break;
      case Phase::kSurface:
        if (fix_in_s > 0) {
          fix_in_s -= dt;
          if (fix_in_s <= 0) navigation.first_gps_fix(noise);
        } else {
          navigation.gps_fix(noise, dt);
        }
        surface_left_s -= dt;
        if (surface_left_s <= 0 && fix_in_s <= 0) {
          phase = Phase::kSubmerged;
          navigation.start_dive(noise);
          surface_at_s = t + noise.uniform(30 * 60, 75 * 60);
        }
        break;
    }
    const double d = depth.step(command, dt);
    const double wander = phase == Phase::kSurface ? 0 : depth_wander.step(noise, dt);
    const std::array<double, 2> logged = navigation.error();
    // The INS follows the wave orbits the vehicle rides (DVL and
    // accelerometers both see them).
    const std::array<double, 3> orbit = waves.displacement(t, d);
    fixes.push_back(telemetry::Fix{t,
                                   {x + orbit[0] + logged[0] + 0.01 * noise.normal(),
                                    y + orbit[1] + logged[1] + 0.01 * noise.normal(), -std::max(0.0, d + wander + orbit[2])}});
  }
  return fixes;
}

}  // namespace acomms::eval
