#include "eval/track_generator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "util/splitmix64.h"

namespace acomms::eval {
namespace {

constexpr double kPi = std::numbers::pi;

// A standard normal deviate (Box-Muller on SplitMix64's uniforms).
double normal(util::SplitMix64& random) {
  const double u1 = 1 - random.uniform();  // (0, 1]
  const double u2 = random.uniform();
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
}

double wrap_angle(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a < -kPi) a += 2 * kPi;
  return a;
}

// A first-order Gauss-Markov process: mean 0, standard deviation sigma,
// correlation time tc, stepped by dt.
struct GaussMarkov {
  double sigma, tc, value = 0;
  double step(util::SplitMix64& random, double dt) {
    const double a = std::exp(-dt / tc);
    value = a * value + sigma * std::sqrt(1 - a * a) * normal(random);
    return value;
  }
};

struct VehicleParams {
  double speed_mps;
  double pitch_rate_mps;  // vertical speed
  double depth_min_m, depth_max_m;
  double turn_rate_rad_s;
  double fix_interval_s;
  double surface_every_s;  // start an ascent after this long submerged
  double surface_stay_s;   // no fixes while at the surface
  double drift_speed_mps;  // navigation drift velocity scale (per dive)
  double jitter_m;         // white noise on the reported x, y
  double heading_wander_rad;
  double current_mps;      // tidal current amplitude (unknown to the nav)
  std::vector<std::array<double, 2>> waypoints;
};

VehicleParams params_of(TrackKind kind) {
  VehicleParams p;
  if (kind == TrackKind::kAuv) {
    p = {1.5, 1.5 * std::sin(15 * kPi / 180), 5, 45, 4 * kPi / 180, 5, 3600, 150, 0.02, 0.1, 1.0 * kPi / 180, 0, {}};
    for (int leg = 0; leg < 40; ++leg) {
      const double y = 150.0 * leg;
      const double x0 = leg % 2 == 0 ? 0 : 1500, x1 = leg % 2 == 0 ? 1500 : 0;
      p.waypoints.push_back({x0, y});
      p.waypoints.push_back({x1, y});
    }
  } else {
    p = {0.3, 0.15, 1, 150, 2 * kPi / 180, 10, 2 * 2 * 149 / 0.15 - 60, 600, 0.03, 0.5, 4.0 * kPi / 180, 0.15, {}};
    p.waypoints = {{0, 0}, {4000, 0}, {4000, 4000}, {0, 4000}, {0, 0}, {4000, 0}, {4000, 4000}, {0, 4000}};
  }
  return p;
}

}  // namespace

TrackKind track_kind_of(const std::string& name) {
  if (name == "auv") return TrackKind::kAuv;
  if (name == "glider") return TrackKind::kGlider;
  throw std::invalid_argument("unknown track kind '" + name + "': use auv or glider");
}

std::vector<telemetry::Fix> generate_track(TrackKind kind, uint64_t seed, double duration_s) {
  const VehicleParams p = params_of(kind);
  util::SplitMix64 random(seed);
  constexpr double dt = 1;
  double x = p.waypoints[0][0], y = p.waypoints[0][1] - 50, z = 0;
  double heading = kPi / 2;
  size_t waypoint = 0;
  bool descending = true;
  double submerged_s = 0, surface_left_s = 0;
  bool ascending_to_surface = false;
  // navigation error: a drift velocity drawn per dive, integrated
  double err_x = 0, err_y = 0, drift_vx = 0, drift_vy = 0;
  // the current as last estimated at the surface (what the nav assumes)
  double estimate_cx = p.current_mps, estimate_cy = 0;
  GaussMarkov speed_noise{0.03 * p.speed_mps, 120}, heading_noise{p.heading_wander_rad, 60};
  auto new_dive = [&] {
    drift_vx = p.drift_speed_mps * normal(random);
    drift_vy = p.drift_speed_mps * normal(random);
  };
  new_dive();
  std::vector<telemetry::Fix> fixes;
  double next_fix = 0;
  for (double t = 0; t <= duration_s; t += dt) {
    if (surface_left_s > 0) {
      // At the surface: drifting with the current, no fixes; the GPS fix at
      // the end removes the navigation error (the jump the telemetry sees).
      surface_left_s -= dt;
      if (surface_left_s <= 0) {
        err_x = err_y = 0;
        const double phase = 2 * kPi * t / (12.42 * 3600);
        estimate_cx = p.current_mps * std::cos(phase);
        estimate_cy = p.current_mps * std::sin(phase);
        new_dive();
        descending = true;
        submerged_s = 0;
        next_fix = t;
      }
    } else {
      // Steer for the waypoint with a bounded turn rate.
      const auto& target = p.waypoints[waypoint];
      if (std::hypot(target[0] - x, target[1] - y) < 20) waypoint = (waypoint + 1) % p.waypoints.size();
      const double want = std::atan2(target[1] - y, target[0] - x);
      const double turn = std::clamp(wrap_angle(want - heading), -p.turn_rate_rad_s * dt, p.turn_rate_rad_s * dt);
      heading = wrap_angle(heading + turn);
      const double actual_heading = heading + heading_noise.step(random, dt);
      const double speed = p.speed_mps + speed_noise.step(random, dt);
      const double current_phase = 2 * kPi * t / (12.42 * 3600);
      const double cx = p.current_mps * std::cos(current_phase), cy = p.current_mps * std::sin(current_phase);
      x += (speed * std::cos(actual_heading) + cx) * dt;
      y += (speed * std::sin(actual_heading) + cy) * dt;
      // The vehicle's navigation knows only the current it estimated at the
      // last surfacing.
      err_x += (drift_vx + estimate_cx - cx) * dt;
      err_y += (drift_vy + estimate_cy - cy) * dt;
      // Depth: yo-yo (or sawtooth), then up to the surface when it is time.
      submerged_s += dt;
      if (submerged_s >= p.surface_every_s) ascending_to_surface = true;
      if (ascending_to_surface) {
        z = std::min(0.0, z + p.pitch_rate_mps * dt);
        if (z >= 0) {
          ascending_to_surface = false;
          surface_left_s = p.surface_stay_s;
        }
      } else {
        z += (descending ? -1 : 1) * p.pitch_rate_mps * dt;
        if (-z >= p.depth_max_m) descending = false;
        if (-z <= p.depth_min_m && !descending) descending = true;
      }
    }
    if (surface_left_s <= 0 && t >= next_fix) {
      telemetry::Fix fix;
      fix.time_s = t;
      fix.position_m = {x + err_x + p.jitter_m * normal(random), y + err_y + p.jitter_m * normal(random),
                        std::min(0.0, z + 0.05 * normal(random))};
      fixes.push_back(fix);
      next_fix = t + p.fix_interval_s;
    }
  }
  return fixes;
}

std::string format_track_csv(const std::vector<telemetry::Fix>& fixes) {
  std::string out = "t,x,y,z\n";
  char line[128];
  for (const telemetry::Fix& fix : fixes) {
    std::snprintf(line, sizeof line, "%.0f,%.2f,%.2f,%.2f\n", fix.time_s, fix.position_m[0], fix.position_m[1],
                  fix.position_m[2]);
    out += line;
  }
  return out;
}

}  // namespace acomms::eval
