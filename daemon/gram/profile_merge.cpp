// Cast merging and thinning: shared/spec/gram.md §2.6.
#include "gram/profile_merge.h"

#include <cmath>

namespace acomms::gram {
namespace {

SoundSpeedPoint point(double z, double c) {
  SoundSpeedPoint p;
  p.set_depth_m(z);
  p.set_speed_mps(c);
  return p;
}

// Linear interpolation of `profile` at z (held constant beyond its ends).
double speed_at(const Profile& profile, double z) {
  if (z <= profile.front().depth_m()) return profile.front().speed_mps();
  for (std::size_t i = 1; i < profile.size(); ++i)
    if (z <= profile[i].depth_m()) {
      const auto& a = profile[i - 1];
      const auto& b = profile[i];
      return a.speed_mps() + (b.speed_mps() - a.speed_mps()) * (z - a.depth_m()) / (b.depth_m() - a.depth_m());
    }
  return profile.back().speed_mps();
}

void append(Profile& out, double z, double c) {
  if (out.empty() || z > out.back().depth_m()) out.push_back(point(z, c));
}

}  // namespace

Profile merge_cast(const Profile& base, const Profile& cast, CastMerge mode) {
  const double surface = base.front().depth_m(), bottom = base.back().depth_m();
  // The cast within the water column (a point at the bottom if it goes beyond).
  Profile measured;
  for (const auto& p : cast)
    if (p.depth_m() >= surface && p.depth_m() <= bottom) measured.push_back(p);
  if (cast.back().depth_m() > bottom) append(measured, bottom, speed_at(cast, bottom));
  if (measured.empty()) return base;
  const double top = measured.front().depth_m(), deepest = measured.back().depth_m();

  Profile out;
  if (mode == CastMerge::kMerge) {
    for (const auto& p : base)
      if (p.depth_m() < top) append(out, p.depth_m(), p.speed_mps());
    for (const auto& p : measured) append(out, p.depth_m(), p.speed_mps());
    for (const auto& p : base)
      if (p.depth_m() > deepest) append(out, p.depth_m(), p.speed_mps());
    return out;
  }
  append(out, surface, measured.front().speed_mps());
  for (const auto& p : measured) append(out, p.depth_m(), p.speed_mps());
  if (mode == CastMerge::kOverwriteWithBaseBelow) {
    for (const auto& p : base)
      if (p.depth_m() > deepest) append(out, p.depth_m(), p.speed_mps());
  }
  append(out, bottom, out.back().speed_mps());
  return out;
}

Profile thin_profile(const Profile& profile, double tolerance) {
  if (profile.size() <= 2) return profile;
  Profile out{profile.front()};
  std::size_t anchor = 0;
  for (std::size_t end = 2; end < profile.size(); ++end) {
    // Can the line anchor→end stand for every point between them?
    const auto& a = profile[anchor];
    const auto& b = profile[end];
    bool fits = true;
    for (std::size_t k = anchor + 1; k < end && fits; ++k) {
      const double t = (profile[k].depth_m() - a.depth_m()) / (b.depth_m() - a.depth_m());
      fits = std::abs(a.speed_mps() + t * (b.speed_mps() - a.speed_mps()) - profile[k].speed_mps()) <= tolerance;
    }
    if (!fits) {
      anchor = end - 1;
      out.push_back(profile[anchor]);
    }
  }
  out.push_back(profile.back());
  return out;
}

}  // namespace acomms::gram
