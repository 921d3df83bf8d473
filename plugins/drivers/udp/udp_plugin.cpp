// "udp" by name: adds the driver to link::DriverRegistry::linked(). It
// needs the core event loop for its socket.

#include <stdexcept>

#include "link/driver_registry.h"
#include "udp/udp_driver.h"

namespace acomms::drivers {
namespace {

const link::DriverRegistrar registrar("udp", [](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
  if (context.io_context == nullptr) {
    throw std::invalid_argument("driver \"udp\" needs the core event loop (DriverContext::io_context)");
  }
  return std::make_unique<UdpDriver>(context.config, context.scheduler, *context.io_context);
});

}  // namespace
}  // namespace acomms::drivers
