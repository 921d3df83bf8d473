// Sound speed profile evaluation: shared/spec/gram.md §1.1.
#include "gram/sound_speed_profile.h"

#include <algorithm>

namespace acomms::gram {

SoundSpeedProfile::SoundSpeedProfile(const Environment& env) {
  for (const auto& point : env.sound_speed()) {
    depth_.push_back(point.depth_m());
    speed_.push_back(point.speed_mps());
  }
  if (env.interpolation() == SSP_CUBIC_SPLINE) spline_.emplace(depth_, speed_);
  for (std::size_t i = 0; i + 1 < depth_.size(); ++i)
    gradient_.push_back((speed_[i + 1] - speed_[i]) / (depth_[i + 1] - depth_[i]));
}

SoundSpeedProfile::Value SoundSpeedProfile::spline_at(double z, std::size_t i) const {
  const auto v = spline_->evaluate(i, z);
  return {v.f, v.df, v.d2f};
}

std::size_t SoundSpeedProfile::layer_at(double z, double heading_dz) const {
  const std::size_t last = depth_.size() - 2;
  if (z <= depth_.front()) return 0;
  if (z >= depth_.back()) return last;
  // First node strictly above z... i.e. depth_[i] <= z < depth_[i+1].
  auto it = std::upper_bound(depth_.begin(), depth_.end(), z);
  std::size_t i = static_cast<std::size_t>(it - depth_.begin()) - 1;
  if (z == depth_[i] && heading_dz < 0 && i > 0) --i;  // on a node heading up
  return std::min(i, last);
}

}  // namespace acomms::gram
