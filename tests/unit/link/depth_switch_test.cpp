// enable_above_depth_m (link/depth_switch.h): a link is switched only when
// the vehicle's depth crosses the threshold, so an operator's enable or
// disable holds between crossings.

#include "link/depth_switch.h"

#include <gtest/gtest.h>

namespace acomms::link {
namespace {

TEST(DepthSwitch, FirstFixSaysWhichSideAndLaterOnesOnlyWhenTheyCross) {
  DepthSwitch shallow(1.5);
  EXPECT_EQ(shallow.on_depth(0.3), std::optional<bool>(true));
  EXPECT_EQ(shallow.on_depth(1.0), std::nullopt) << "still above: nothing to say";
  EXPECT_EQ(shallow.on_depth(1.5), std::optional<bool>(false)) << "at the threshold is not shallower";
  EXPECT_EQ(shallow.on_depth(40), std::nullopt);
  EXPECT_EQ(shallow.on_depth(1.49), std::optional<bool>(true));

  DepthSwitch deep(1.5);
  EXPECT_EQ(deep.on_depth(20), std::optional<bool>(false));
}

}  // namespace
}  // namespace acomms::link
