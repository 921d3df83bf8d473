// "micromodem" by name: adds the WHOI Micro-Modem driver to
// link::DriverRegistry::linked(). Its port (serial or TCP) runs on the core
// event loop.

#include <stdexcept>

#include "link/driver_registry.h"
#include "micromodem/micromodem_driver.h"

namespace acomms::drivers::micromodem {
namespace {

const link::DriverRegistrar registrar("micromodem",
                                      [](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
  if (context.io_context == nullptr) {
    throw std::invalid_argument("driver \"micromodem\" needs the core event loop (DriverContext::io_context)");
  }
  const auto& settings = context.config.micromodem();
  return std::make_unique<MicroModemDriver>(context.config, context.scheduler,
                                            transport_port(settings.port(), settings.baud(), *context.io_context));
});

}  // namespace
}  // namespace acomms::drivers::micromodem
