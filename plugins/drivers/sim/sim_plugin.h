#pragma once
// "sim" by name. sim_plugin.cpp adds it to link::DriverRegistry::linked():
// a loopback node from driver.sim (listen/peers), or an isolated one.
//
// Several simulated nodes in one process (on one SimulatedScheduler, e.g.
// `acommsctl sim` or a system test) share a SimChannel instead: replace
// "sim" in a copy of the registry so that every node it builds joins it.

#include <memory>

#include "link/driver_registry.h"
#include "sim/sim_channel.h"
#include "sim/tl_grid_source.h"

namespace acomms::drivers {

// `model`: where nodes with sim.physics run the model (the GRAM pool).
void register_sim_channel_driver(link::DriverRegistry& registry, std::shared_ptr<SimChannel> channel,
                                 std::shared_ptr<TlGridSource> model = nullptr);

}  // namespace acomms::drivers
