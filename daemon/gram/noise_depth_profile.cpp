// Noise level with depth: shared/spec/gram.md §6.6.
#include "gram/noise_depth_profile.h"

#include <algorithm>

namespace acomms::gram {

std::optional<double> critical_depth(const Environment& env) {
  const auto& p = env.sound_speed();
  if (p.size() < 2) return std::nullopt;
  int axis = 0;  // the first point of least speed
  for (int i = 1; i < p.size(); ++i)
    if (p[i].speed_mps() < p[axis].speed_mps()) axis = i;
  double above = 0;  // the largest speed at or above the axis
  for (int i = 0; i <= axis; ++i) above = std::max(above, p[i].speed_mps());
  // Least speed at the surface (isovelocity, a surface duct): no channel.
  if (!(p[axis].speed_mps() < above)) return std::nullopt;
  for (int i = axis + 1; i < p.size(); ++i) {
    if (p[i].speed_mps() < above) continue;
    // Regained between point i−1 (below `above`) and point i: c linear.
    const double c0 = p[i - 1].speed_mps(), c1 = p[i].speed_mps();
    const double t = (above - c0) / (c1 - c0);
    return p[i - 1].depth_m() + t * (p[i].depth_m() - p[i - 1].depth_m());
  }
  return std::nullopt;
}

double noise_level_at_depth(double nl0_db, double depth_m, std::optional<double> critical_depth_m,
                            double decrease_db_per_km) {
  if (!critical_depth_m || depth_m <= *critical_depth_m) return nl0_db;
  return nl0_db - decrease_db_per_km * (depth_m - *critical_depth_m) / 1000.0;
}

}  // namespace acomms::gram
