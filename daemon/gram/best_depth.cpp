// Best depth within the vehicle's limits (see best_depth.h).
#include "gram/best_depth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gram/validation_text.h"

namespace acomms::gram {

std::optional<std::string> validate_limits(const VehicleLimits& l) {
  if (auto e = require_at_least("limits.min_depth_m", l.min_depth_m, 0.0)) return e;
  if (auto e = require_at_least("limits.max_depth_m", l.max_depth_m, l.min_depth_m))
    return *e + " (limits.min_depth_m)";
  return require_at_least("limits.min_altitude_m", l.min_altitude_m, 0.0);
}

double bottom_depth_at(const Environment& env, double r) {
  const auto& b = env.bathymetry();
  if (b.empty()) return env.sound_speed(env.sound_speed_size() - 1).depth_m();
  if (r <= b[0].range_m()) return b[0].depth_m();
  for (int i = 1; i < b.size(); ++i) {
    if (r <= b[i].range_m()) {
      const double t = (r - b[i - 1].range_m()) / (b[i].range_m() - b[i - 1].range_m());
      return b[i - 1].depth_m() + t * (b[i].depth_m() - b[i - 1].depth_m());
    }
  }
  return b[b.size() - 1].depth_m();
}

double shallowest_bottom(const Environment& env, const RangeWindow& w) {
  // Piecewise linear: the minimum is at an end or at a bathymetry point inside.
  double z = std::min(bottom_depth_at(env, w.begin_m), bottom_depth_at(env, w.end_m));
  for (const auto& p : env.bathymetry())
    if (p.range_m() > w.begin_m && p.range_m() < w.end_m) z = std::min(z, p.depth_m());
  return z;
}

BestDepth best_depth(std::span<const double> depth_m, std::span<const double> objective,
                     const VehicleLimits& limits, double bottom_m) {
  if (auto e = validate_limits(limits)) throw std::invalid_argument(*e);
  if (depth_m.size() != objective.size())
    throw std::invalid_argument("the objective has " + std::to_string(objective.size()) +
                                " values for " + std::to_string(depth_m.size()) + " depths");
  BestDepth best;
  best.deepest_allowed_m = std::min(limits.max_depth_m, bottom_m - limits.min_altitude_m);
  bool found = false;
  for (std::size_t i = 0; i < depth_m.size(); ++i) {
    const double d = depth_m[i];
    if (d < limits.min_depth_m || d > best.deepest_allowed_m) continue;
    const double o = std::isnan(objective[i]) ? 0.0 : objective[i];
    const bool better = !found || o > best.objective + kObjectiveTie ||
                        (std::abs(o - best.objective) <= kObjectiveTie && d < best.depth_m);
    if (better) {
      best.index = i;
      best.depth_m = d;
      best.objective = o;
      found = true;
    }
  }
  if (!found) {
    std::string grid = depth_m.empty() ? "none"
                                       : format_number(depth_m.front()) + " to " +
                                             format_number(depth_m.back()) + " m";
    throw std::invalid_argument(
        "no receiver depth lies within the vehicle's limits [" + format_number(limits.min_depth_m) +
        ", " + format_number(best.deepest_allowed_m) + "] m (max_depth_m " +
        format_number(limits.max_depth_m) + ", bottom " + format_number(bottom_m) +
        " m − min_altitude_m " + format_number(limits.min_altitude_m) + "; grid depths " + grid +
        ")");
  }
  best.any_signal = best.objective > 0;
  return best;
}

}  // namespace acomms::gram
