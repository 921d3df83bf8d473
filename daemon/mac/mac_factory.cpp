#include "mac/mac_factory.h"

#include <cmath>
#include <optional>
#include <stdexcept>

#include "mac/auto_discovery_mac.h"
#include "mac/fixed_mac.h"
#include "mac/polled_mac.h"
#include "mac/silent_mac.h"

namespace acomms::mac {
namespace {

std::string joined_names() {
  std::string out;
  for (const std::string& name : mac_names()) out += (out.empty() ? "\"" : ", \"") + name + "\"";
  return out;
}

std::optional<double> epoch_of(const v1::MacConfig& config) {
  if (!config.has_epoch()) return std::nullopt;
  if (!std::isfinite(config.epoch()))
    throw std::invalid_argument("mac.epoch must be a finite number of seconds since 1970");
  return config.epoch();
}

void check_own_id(int32_t own_id, const std::string& name) {
  if (own_id < 1)
    throw std::invalid_argument("mac \"" + name + "\" needs this node's modem id >= 1, got " +
                                std::to_string(own_id));
}

}  // namespace

std::vector<std::string> mac_names() { return {"auto_discovery", "fixed", "none", "polled"}; }

Cycle cycle_from_config(const v1::MacConfig& config) {
  Cycle cycle;
  for (const v1::MacSlot& configured : config.slot()) {
    Slot slot;
    slot.src = configured.src();
    slot.dest = configured.has_dest() ? configured.dest() : -1;
    slot.rate = configured.rate();
    slot.seconds = configured.seconds();
    slot.type = v1::ModemTransmission::DATA;
    cycle.push_back(slot);
  }
  return cycle;
}

std::unique_ptr<Mac> make_mac(const v1::MacConfig& config, int32_t own_id,
                              core::Scheduler& scheduler) {
  const std::string& name = config.name();
  if (config.has_max_range_m() && !(config.max_range_m() >= 0 && std::isfinite(config.max_range_m())))
    throw std::invalid_argument("mac.max_range_m must be a finite number of metres >= 0 (unset: 2000), got " +
                                std::to_string(config.max_range_m()));
  if (name.empty() || name == "none") return std::make_unique<SilentMac>();
  if (name == "polled" || name == "fixed") {
    Cycle cycle = cycle_from_config(config);
    check_cycle(cycle, "mac.slot");
    if (name == "polled") return std::make_unique<PolledMac>(std::move(cycle), scheduler);
    check_own_id(own_id, name);
    std::optional<double> epoch = epoch_of(config);
    if (!epoch && cycle_seconds(cycle) > 86400)
      throw std::invalid_argument(
          "mac.slot: a \"fixed\" cycle longer than a day (" + std::to_string(cycle_seconds(cycle)) +
          " s) cannot realign at midnight UTC; set mac.epoch");
    return std::make_unique<FixedMac>(std::move(cycle), own_id, epoch, scheduler);
  }
  if (name == "auto_discovery") {
    if (config.slot_size() > 0)
      throw std::invalid_argument(
          "mac.slot is not used by \"auto_discovery\" (its cycle comes from the nodes it hears); "
          "remove it or use \"fixed\"");
    check_own_id(own_id, name);
    AutoDiscoveryConfig auto_config;
    auto_config.slot_seconds = config.slot_seconds();
    auto_config.rate = config.rate();
    auto_config.coolness = config.coolness();
    auto_config.expire_cycles = config.expire_cycles();
    auto_config.epoch = epoch_of(config);
    const std::string& rule = config.blank_rule();
    std::optional<BlankRule> named = blank_rule_from_name(rule);
    if (rule.empty()) {
      auto_config.blank_rule = kDefaultBlankRule;
    } else if (named) {
      auto_config.blank_rule = *named;
    } else {
      throw std::invalid_argument("mac.blank_rule \"" + rule +
                                  "\" is unknown; known: \"anywhere\" (default), \"figure\", "
                                  "\"congruence\"");
    }
    return std::make_unique<AutoDiscoveryMac>(auto_config, own_id, scheduler);
  }
  throw std::invalid_argument("mac.name \"" + name + "\" is unknown; known: " + joined_names());
}

}  // namespace acomms::mac
