#pragma once
// `acommsd --check-config`: the slots that cannot carry one frame.
//
// A slot too short for even one frame at its rate (its air time, the ACK,
// the sound's travel to mac.max_range_m and back; link/slot_budget.h) sends
// no data at all, every cycle. That is a config mistake, but not an error:
// the node still listens, and a longer slot elsewhere in the cycle may be
// the one that matters. So the check warns, one line per such slot, and
// the config still passes.
//
// Thread-safe: the first form only reads the driver's const timing figures;
// the second builds its own driver, never started, and shares nothing
// (acommsd runs it for --check-config, before any core thread).

#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "link/driver.h"
#include "link/driver_registry.h"

namespace acomms::link {

// One line per slot of `mac` that cannot carry one frame with `driver`'s
// timing, an ACK requested: "mac slot 2 (src 2, rate 5, 4 s) cannot carry
// one frame: one frame needs ...". auto_discovery's slots are one line
// ("mac auto_discovery slots (rate 5, 4 s) ..."). Throws
// std::invalid_argument for a bad mac.max_range_m.
std::vector<std::string> short_slot_warnings(const v1::MacConfig& mac, const Driver& driver);

// The same for each of the config's links (core/node_links.h) with its own
// driver, built (never started) from `registry` for its timing; when it
// cannot be built, a real modem's defaults (driver.h) are used. With
// several links each line begins "link NAME: ".
std::vector<std::string> short_slot_warnings(const v1::Config& config, const DriverRegistry& registry);

}  // namespace acomms::link
