// Prepared environment: shared/spec/gram.md §1, §3.3, §4.3.
#include "gram/medium.h"

#include <algorithm>
#include <limits>
#include <numbers>

#include "gram/absorption.h"
#include "gram/environment_validation.h"

namespace acomms::gram {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double volume_attenuation(const Environment& env) {
  const double f_khz = env.frequency_hz() / 1000.0;
  const auto& a = env.attenuation();
  switch (a.kind()) {
    case VolumeAttenuation::THORP:
      return thorp_absorption(f_khz) / kDbPerKmPerNeperPerM;
    case VolumeAttenuation::FRANCOIS_GARRISON:
      // Evaluated once at the mean depth, as BELLHOP's 'F' option (spec §3.2).
      return francois_garrison_absorption(f_khz, a.temperature_degc(), a.salinity_ppt(), a.ph(),
                                          a.mean_depth_m()).total() / kDbPerKmPerNeperPerM;
    default:
      return 0.0;
  }
}

std::vector<BottomSegment> make_bottom_segments(const Environment& env) {
  const auto& b = env.bathymetry();
  if (b.empty()) return {{-kInf, kInf, env.sound_speed(env.sound_speed_size() - 1).depth_m(), 0.0}};
  std::vector<BottomSegment> s;
  s.push_back({-kInf, b[0].range_m(), b[0].depth_m(), 0.0});
  for (int i = 0; i + 1 < b.size(); ++i) {
    const double dr = b[i + 1].range_m() - b[i].range_m();
    s.push_back({b[i].range_m(), b[i + 1].range_m(), b[i].depth_m(),
                 (b[i + 1].depth_m() - b[i].depth_m()) / dr});
  }
  s.push_back({b[b.size() - 1].range_m(), kInf, b[b.size() - 1].depth_m(), 0.0});
  return s;
}

}  // namespace

Medium::Medium(const Environment& env)
    : ssp_(env),
      surface_(env.surface()),
      bottom_(env.bottom()),
      segments_(make_bottom_segments(env)),
      frequency_(env.frequency_hz()),
      omega_(2.0 * std::numbers::pi * env.frequency_hz()),
      volume_np_per_m_(volume_attenuation(env)),
      box_depth_(env.box_depth_m()),
      box_range_(env.box_range_m()),
      water_depth_(deepest_bottom(env) - env.sound_speed(0).depth_m()),
      source_depth_(env.source_depth_m()) {
  max_step_ = env.step_m() > 0 ? env.step_m() : water_depth_ / 10.0;
}

std::size_t Medium::segment_at(double r) const {
  // Segments are ordered; the first whose end lies beyond r.
  auto it = std::upper_bound(segments_.begin(), segments_.end(), r,
                             [](double x, const BottomSegment& s) { return x < s.r1; });
  return std::min<std::size_t>(static_cast<std::size_t>(it - segments_.begin()), segments_.size() - 1);
}

}  // namespace acomms::gram
