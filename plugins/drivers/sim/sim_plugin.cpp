#include "sim/sim_plugin.h"

#include "sim/sim_driver.h"

namespace acomms::drivers {
namespace {

const link::DriverRegistrar registrar("sim", [](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
  auto driver = std::make_unique<SimDriver>(context.config, context.scheduler, context.io_context);
  driver->set_position_source(context.node_position);
  return driver;
});

}  // namespace

void register_sim_channel_driver(link::DriverRegistry& registry, std::shared_ptr<SimChannel> channel) {
  registry.add("sim", [channel](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
    auto driver = std::make_unique<SimDriver>(context.config, context.scheduler, channel);
    driver->set_position_source(context.node_position);
    return driver;
  });
}

}  // namespace acomms::drivers
