#pragma once
// Where a simulated node is now, asked by its SimDriver whenever it sends
// or hears a packet.
//
// Problem: a moving vehicle's position comes from its navigation (the
// daemon's navigation input, SubmitNavigation), not from the sim config.
// Decision: the driver reads its position through this one-method
// interface; without a source it uses the config's position (and
// set_position()). Wiring the navigation input is then one line:
// driver.set_position_source(<the node's navigation>).
// Thread rules: position() is called on the core thread.

#include "sim/sim_envelope.h"

namespace acomms::drivers {

class NodePositionSource {
 public:
  virtual ~NodePositionSource() = default;
  // x, y, z in sim.proto's frame (z up: depth is −z).
  virtual SimPosition position() const = 0;
};

}  // namespace acomms::drivers
