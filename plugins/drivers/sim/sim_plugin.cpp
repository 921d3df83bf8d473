#include "sim/sim_plugin.h"

#include "sim/navigation_position.h"
#include "sim/sim_driver.h"

namespace acomms::drivers {
namespace {

// The daemon's navigation input, when the context has one: the node moves
// with the vehicle's fixes (SubmitNavigation).
void follow_navigation(SimDriver& driver, const link::DriverContext& context) {
  if (context.node_position == nullptr) return;
  driver.set_position_source(std::make_shared<NavigationPosition>(context.node_position, driver.position()));
}

const link::DriverRegistrar registrar("sim", [](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
  auto driver = std::make_unique<SimDriver>(context.config, context.scheduler, context.io_context, context.models);
  follow_navigation(*driver, context);
  return driver;
});

}  // namespace

void register_sim_channel_driver(link::DriverRegistry& registry, std::shared_ptr<SimChannel> channel,
                                 std::shared_ptr<TlGridSource> model) {
  registry.add("sim", [channel, model](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
    auto driver = std::make_unique<SimDriver>(context.config, context.scheduler, channel);
    if (model) driver->set_tl_grid_source(model);
    follow_navigation(*driver, context);
    return driver;
  });
}

}  // namespace acomms::drivers
