#pragma once
// The daemon's navigation input (SubmitNavigation, core/node_position.h) as
// the sim driver's NodePositionSource: the newest fix, or the config's
// position until the first fix comes. This is how a moving simulated
// vehicle needs nothing but its navigation.

#include <memory>

#include "core/node_position.h"
#include "sim/node_position_source.h"

namespace acomms::drivers {

class NavigationPosition final : public NodePositionSource {
 public:
  // `navigation` must outlive this source (the daemon owns both).
  NavigationPosition(const core::NodePosition* navigation, const SimPosition& before_first_fix)
      : navigation_(navigation), before_first_fix_(before_first_fix) {}

  SimPosition position() const override {
    if (std::optional<core::NodeFix> fix = navigation_->latest()) return SimPosition{fix->x, fix->y, fix->z};
    return before_first_fix_;
  }

 private:
  const core::NodePosition* navigation_;
  SimPosition before_first_fix_;
};

}  // namespace acomms::drivers
