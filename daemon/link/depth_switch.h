#pragma once
// When a link is enabled by the vehicle's depth (LinkConfig
// enable_above_depth_m): a satellite modem is only of use at the surface,
// and a session tried underwater only fails and drains the battery.
//
// Edge-triggered on purpose: a fix shallower than the threshold after one
// deeper (or the first fix of all) says "enable", a deeper one after a
// shallower says "disable", and fixes on the same side say nothing. So an
// operator's `acommsctl link enable|disable` holds until the vehicle next
// crosses the threshold, instead of being undone by the next fix.
//
// Thread-compatible: one owner (the daemon's core thread).

#include <optional>

namespace acomms::link {

class DepthSwitch {
 public:
  explicit DepthSwitch(double enable_above_depth_m) : threshold_m_(enable_above_depth_m) {}

  // A navigation fix at `depth_m` (positive down). The link's new state when
  // this fix crossed the threshold; nullopt otherwise.
  std::optional<bool> on_depth(double depth_m) {
    const bool shallow = depth_m < threshold_m_;
    if (side_ && *side_ == shallow) return std::nullopt;
    side_ = shallow;
    return shallow;
  }

  double threshold_m() const { return threshold_m_; }

 private:
  double threshold_m_;
  std::optional<bool> side_;  // shallow at the last fix; nullopt before the first
};

}  // namespace acomms::link
