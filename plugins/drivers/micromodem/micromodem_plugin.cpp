// "micromodem" by name: adds the WHOI Micro-Modem driver to
// link::DriverRegistry::linked(). Its port (serial or TCP) runs on the core
// event loop. Its NMEA sentences are kept in the raw link log
// (link/raw_log.h): what the modem said is what someone debugging a link at
// sea asks for days later.

#include <stdexcept>

#include "link/driver_registry.h"
#include "micromodem/micromodem_driver.h"

namespace acomms::drivers::micromodem {
namespace {

// Where the raw log rotates unless driver.micromodem.raw_log_bytes says.
constexpr uint64_t kDefaultRawLogBytes = uint64_t{4} << 20;

link::DriverTraits traits() {
  link::DriverTraits traits;
  traits.raw_log_bytes = [](const v1::DriverConfig& config) {
    const uint64_t bytes = config.micromodem().raw_log_bytes();
    return bytes == 0 ? kDefaultRawLogBytes : bytes;
  };
  return traits;
}

const link::DriverRegistrar registrar("micromodem",
                                      [](const link::DriverContext& context) -> std::unique_ptr<link::Driver> {
  if (context.io_context == nullptr) {
    throw std::invalid_argument("driver \"micromodem\" needs the core event loop (DriverContext::io_context)");
  }
  const auto& settings = context.config.micromodem();
  return std::make_unique<MicroModemDriver>(context.config, context.scheduler,
                                            transport_port(settings.port(), settings.baud(), *context.io_context));
}, traits());

}  // namespace
}  // namespace acomms::drivers::micromodem
