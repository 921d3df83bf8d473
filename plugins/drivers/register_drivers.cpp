#include "register_drivers.h"

#include <stdexcept>

#include "sim/sim_channel.h"
#include "sim/sim_driver.h"
#include "udp/udp_driver.h"

namespace acomms {

void register_builtin_drivers(link::DriverRegistry& registry) {
  registry.add("sim", [](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
    return std::make_unique<drivers::SimDriver>(context.config, context.scheduler, context.io_context);
  });
  registry.add("udp", [](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
    if (context.io_context == nullptr) {
      throw std::invalid_argument("driver \"udp\" needs the core event loop (DriverContext::io_context)");
    }
    return std::make_unique<drivers::UdpDriver>(context.config, context.scheduler, *context.io_context);
  });
}

void register_sim_channel_driver(link::DriverRegistry& registry, std::shared_ptr<drivers::SimChannel> channel) {
  registry.add("sim", [channel](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
    return std::make_unique<drivers::SimDriver>(context.config, context.scheduler, channel);
  });
}

}  // namespace acomms
