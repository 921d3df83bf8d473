#include "link/slot_check.h"

#include "core/node_links.h"

#include <asio/io_context.hpp>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/scheduler.h"
#include "link/rate_table.h"
#include "link/slot_budget.h"
#include "mac/mac.h"
#include "mac/mac_factory.h"

namespace acomms::link {

namespace {

// A driver that is only its timing: the defaults of driver.h.
class DefaultTiming final : public Driver {
 public:
  void start(DriverCallbacks) override {}
  void stop() override {}
  void do_work() override {}
  void initiate_transmission(const v1::ModemTransmission&) override {}
};

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string shortfall(const Driver& driver, int32_t rate, double seconds, double max_range_m) {
  SlotBudget budget;
  budget.rate = rate;
  budget.time_left = std::chrono::nanoseconds(std::llround(seconds * 1e9));
  budget.ack_requested = true;
  budget.max_range_m = max_range_m;
  if (find_rate(rate) == nullptr || frames_that_fit(driver, budget, 1) > 0) return "";
  return describe_shortfall(driver, budget);
}

}  // namespace

std::vector<std::string> short_slot_warnings(const v1::MacConfig& mac, const Driver& driver) {
  double max_range_m = kDefaultMaxRangeM;
  if (mac.has_max_range_m()) {
    if (!(mac.max_range_m() >= 0 && std::isfinite(mac.max_range_m()))) {
      throw std::invalid_argument("mac.max_range_m must be a finite number of metres >= 0 (unset: 2000), got " +
                                  std::to_string(mac.max_range_m()));
    }
    max_range_m = mac.max_range_m();
  }
  std::vector<std::string> warnings;
  if (mac.name() == "auto_discovery") {
    std::string why = shortfall(driver, mac.rate(), mac.slot_seconds(), max_range_m);
    if (!why.empty()) {
      warnings.push_back("mac auto_discovery slots (rate " + std::to_string(mac.rate()) + ", " +
                         number(mac.slot_seconds()) + " s) cannot carry one frame: " + why);
    }
    return warnings;
  }
  if (mac.name() != "fixed" && mac.name() != "polled") return warnings;
  mac::Cycle cycle = mac::cycle_from_config(mac);
  for (size_t i = 0; i < cycle.size(); ++i) {
    const mac::Slot& slot = cycle[i];
    std::string why = shortfall(driver, slot.rate, slot.seconds, max_range_m);
    if (why.empty()) continue;
    warnings.push_back("mac slot " + std::to_string(i + 1) + " (src " + std::to_string(slot.src) + ", rate " +
                       std::to_string(slot.rate) + ", " + number(slot.seconds) + " s) cannot carry one frame: " + why);
  }
  return warnings;
}

std::vector<std::string> short_slot_warnings(const v1::Config& config, const DriverRegistry& registry) {
  core::SimulatedScheduler scheduler{core::Clock::time_point{}};
  asio::io_context io_context;
  const std::vector<v1::LinkConfig> links = core::node_links(config);
  std::vector<std::string> warnings;
  for (const v1::LinkConfig& link : links) {
    std::unique_ptr<Driver> driver;
    try {
      // Drivers open their device in start(), not when built.
      driver = registry.create(link.driver().name(), {link.driver(), scheduler, &io_context});
    } catch (const std::exception&) {
      // A bad driver block is the daemon's start-up error to report; the
      // slots are still checked, with a real modem's timing.
    }
    if (!driver) driver = std::make_unique<DefaultTiming>();
    for (std::string& warning : short_slot_warnings(link.mac(), *driver)) {
      warnings.push_back(links.size() > 1 ? "link " + link.name() + ": " + warning : std::move(warning));
    }
  }
  return warnings;
}

}  // namespace acomms::link
