#pragma once
// Drivers by name. Each driver plugin (plugins/drivers/<name>) registers a
// factory; the config's driver.name picks one.

#include <asio/io_context.hpp>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "core/scheduler.h"
#include "link/driver.h"

namespace acomms::link {

// What a driver is built with.
struct DriverContext {
  const v1::DriverConfig& config;  // the whole driver section (modem_id, and the driver's own block)
  core::Scheduler& scheduler;      // time and timers (core thread)
  // The core thread's event loop, for drivers with a device or socket
  // ("udp", "sim" over loopback). Null where there is none (tests on the
  // simulated scheduler); such drivers then refuse to be built.
  asio::io_context* io_context = nullptr;
};

using DriverFactory = std::function<std::unique_ptr<Driver>(const DriverContext&)>;

class DriverRegistry {
 public:
  // Registers (or replaces) a driver.
  void add(const std::string& name, DriverFactory factory);
  // Builds the driver `name`. Throws std::invalid_argument naming the known
  // drivers when there is no such driver, or whatever the factory throws for
  // a bad driver config.
  std::unique_ptr<Driver> create(const std::string& name, const DriverContext& context) const;
  std::vector<std::string> names() const;

 private:
  std::map<std::string, DriverFactory> factories_;
};

}  // namespace acomms::link
