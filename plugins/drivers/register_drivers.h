#pragma once
// The drivers built into acommsd, registered by name for the config's
// driver.name: "sim" (acoustic modem simulator) and "udp".

#include <memory>

#include "link/driver_registry.h"

namespace acomms::drivers {
class SimChannel;
}

namespace acomms {

// "sim" builds a loopback node from driver.sim (listen/peers) or an
// isolated one; "udp" needs DriverContext::io_context.
void register_builtin_drivers(link::DriverRegistry& registry);

// Re-registers "sim" so that every node it builds joins `channel`: several
// nodes in one process (on one SimulatedScheduler), e.g. `acommsctl sim`.
void register_sim_channel_driver(link::DriverRegistry& registry, std::shared_ptr<drivers::SimChannel> channel);

}  // namespace acomms
