#include "sim/sim_plugin.h"

#include "sim/sim_driver.h"

namespace acomms::drivers {
namespace {

const link::DriverRegistrar registrar("sim", [](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
  return std::make_unique<SimDriver>(context.config, context.scheduler, context.io_context, context.models);
});

}  // namespace

void register_sim_channel_driver(link::DriverRegistry& registry, std::shared_ptr<SimChannel> channel,
                                 std::shared_ptr<TlGridSource> model) {
  registry.add("sim", [channel, model](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
    auto driver = std::make_unique<SimDriver>(context.config, context.scheduler, channel);
    if (model) driver->set_tl_grid_source(model);
    return driver;
  });
}

}  // namespace acomms::drivers
