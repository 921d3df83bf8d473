// "iridium_shore" by name: adds the driver to link::DriverRegistry::linked().
// It needs the core event loop for its sockets.

#include <stdexcept>

#include "iridium_shore/iridium_shore_driver.h"
#include "link/driver_registry.h"

namespace acomms::drivers {
namespace {

const link::DriverRegistrar registrar(
    "iridium_shore", [](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
      if (context.io_context == nullptr) {
        throw std::invalid_argument("driver \"iridium_shore\" needs the core event loop (DriverContext::io_context)");
      }
      return std::make_unique<IridiumShoreDriver>(context.config, context.scheduler, *context.io_context);
    });

}  // namespace
}  // namespace acomms::drivers
