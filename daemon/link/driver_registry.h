#pragma once
// Drivers by name. Any thread may read the linked registry once main()
// starts; the drivers it builds live on the core thread (driver.h).
// Each driver plugin (plugins/drivers/<name>) adds its
// factory to the drivers linked into the program with a static
// DriverRegistrar in its own .cpp (the plugins' library is linked whole, so
// the linker keeps that object); the daemon takes DriverRegistry::linked()
// and the config's driver.name picks one. Nothing lists the drivers: a new
// driver is a new folder under plugins/drivers. What the daemon does
// differently for one driver, the driver declares about itself when it
// registers (DriverTraits): the daemon names no driver.
//
// linked() is filled during static initialisation only and read only
// afterwards; a DriverRegistry copied from it (a test's, acommsctl's
// simulator) may replace drivers without touching it.

#include <asio/io_context.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "core/node_position.h"
#include "core/scheduler.h"
#include "link/driver.h"

namespace acomms::gram {
class ModelPool;
}

namespace acomms::link {

// What a driver is built with.
struct DriverContext {
  const v1::DriverConfig& config;  // the whole driver section (modem_id, and the driver's own block)
  core::Scheduler& scheduler;      // time and timers (core thread)
  // The core thread's event loop, for drivers with a device or socket
  // ("udp", "sim" over loopback). Null where there is none (tests on the
  // simulated scheduler); such drivers then refuse to be built.
  asio::io_context* io_context = nullptr;
  // Where this node is now (the navigation input, SubmitNavigation), for
  // drivers that model position: the simulator. Null: none (tests), or the
  // driver's own config.
  const core::NodePosition* node_position = nullptr;
  // GRAM's model worker pool (gram/model_pool.h), for drivers that run the
  // acoustic model (the simulator's physics). Null: such a driver brings a
  // thread of its own.
  gram::ModelPool* models = nullptr;
};

using DriverFactory = std::function<std::unique_ptr<Driver>(const DriverContext&)>;

// What a driver says about itself, beyond how it is built.
struct DriverTraits {
  // Whether its bytes are worth keeping in the raw link log (link/raw_log.h),
  // and at what size that log rotates, from the driver section. Unset: not
  // kept (a simulator's or a UDP link's binary datagrams are not worth the
  // disk; a serial modem's sentences are, for whoever debugs it later).
  std::function<uint64_t(const v1::DriverConfig& config)> raw_log_bytes;
};

class DriverRegistry {
 public:
  // The drivers linked into this program, each added by its DriverRegistrar.
  static const DriverRegistry& linked();

  // Registers (or replaces) a driver, with what it says about itself.
  void add(const std::string& name, DriverFactory factory, DriverTraits traits = {});
  // Builds the driver `name`. Throws std::invalid_argument naming the known
  // drivers when there is no such driver, or whatever the factory throws for
  // a bad driver config.
  std::unique_ptr<Driver> create(const std::string& name, const DriverContext& context) const;
  // Throws std::invalid_argument (as create()) when there is no such driver.
  const DriverTraits& traits(const std::string& name) const;
  std::vector<std::string> names() const;

 private:
  struct Entry {
    DriverFactory factory;
    DriverTraits traits;
  };
  const Entry& find(const std::string& name) const;

  std::map<std::string, Entry> drivers_;
};

// Adds driver `name` to DriverRegistry::linked(). Define one as a static
// object in the driver plugin's .cpp.
class DriverRegistrar {
 public:
  DriverRegistrar(const std::string& name, DriverFactory factory, DriverTraits traits = {});
};

}  // namespace acomms::link
