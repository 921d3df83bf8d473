// "iridium" by name: adds the vehicle's Iridium SBD driver to
// link::DriverRegistry::linked(). Its port (serial or TCP) runs on the core
// event loop. Its AT exchanges are kept in the raw link log (link/raw_log.h):
// a session that failed at sea is understood from them days later.

#include <stdexcept>

#include "iridium/iridium_driver.h"
#include "link/driver_registry.h"

namespace acomms::drivers::iridium {
namespace {

// Where the raw log rotates unless driver.iridium.raw_log_bytes says.
constexpr uint64_t kDefaultRawLogBytes = uint64_t{4} << 20;

link::DriverTraits traits() {
  link::DriverTraits traits;
  traits.raw_log_bytes = [](const v1::DriverConfig& config) {
    const uint64_t bytes = config.iridium().raw_log_bytes();
    return bytes == 0 ? kDefaultRawLogBytes : bytes;
  };
  return traits;
}

const link::DriverRegistrar registrar("iridium",
                                      [](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
  if (context.io_context == nullptr) {
    throw std::invalid_argument("driver \"iridium\" needs the core event loop (DriverContext::io_context)");
  }
  const auto& settings = context.config.iridium();
  return std::make_unique<IridiumDriver>(
      context.config, context.scheduler,
      transport_port(settings.port(), settings.baud(), settings.rts_cts(), *context.io_context));
}, traits());

}  // namespace
}  // namespace acomms::drivers::iridium
