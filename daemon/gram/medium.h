// The environment prepared for ray tracing.
//
// Problem: the ray loop must not consult the protobuf message or search the
// profile at every step. Decision: Medium holds the profile (with its
// derivatives), the boundaries, the bottom as piecewise-linear segments
// (a flat bottom is one segment; bathymetry points that do not cover the
// ranges are extended horizontally), the volume attenuation in Np/m and the
// step and box limits. Built once per run from a validated Environment;
// immutable and shared by all tracing threads.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "gram/sound_speed_profile.h"

namespace acomms::gram {

// A straight piece of the bottom over [r0, r1) (r0 may be −∞, r1 +∞).
struct BottomSegment {
  double r0, r1;
  double z0;     // depth at r0 (or everywhere, if flat)
  double slope;  // dz/dr
  double depth_at(double r) const { return z0 + slope * (std::isinf(r0) ? 0.0 : r - r0); }
};

class Medium {
 public:
  // `env` must have passed validate_environment.
  explicit Medium(const Environment& env);

  const SoundSpeedProfile& ssp() const { return ssp_; }
  const Boundary& surface() const { return surface_; }
  const Boundary& bottom() const { return bottom_; }
  const std::vector<BottomSegment>& bottom_segments() const { return segments_; }
  std::size_t segment_at(double r) const;

  double frequency() const { return frequency_; }
  double omega() const { return omega_; }
  double volume_attenuation_np_per_m() const { return volume_np_per_m_; }
  double max_step() const { return max_step_; }
  double box_depth() const { return box_depth_; }
  double box_range() const { return box_range_; }
  double water_depth() const { return water_depth_; }
  double source_depth() const { return source_depth_; }

 private:
  SoundSpeedProfile ssp_;
  Boundary surface_, bottom_;
  std::vector<BottomSegment> segments_;
  double frequency_, omega_, volume_np_per_m_, max_step_, box_depth_, box_range_;
  double water_depth_, source_depth_;
};

}  // namespace acomms::gram
