#pragma once
// Builds the MAC the config names.
//
//   "polled"          PolledMac: this node polls every slot's src in turn.
//   "fixed"           FixedMac: the configured cycle, aligned to UTC; this
//                     node transmits in its own slots.
//   "auto_discovery"  AutoDiscoveryMac: slots from the nodes heard, using
//                     slot_seconds, rate, coolness, expire_cycles, blank_rule
//                     (and epoch).
//   "none" (or unset) SilentMac: never initiates (answers polls only).
//
// Bad configs throw std::invalid_argument naming the field and the bound:
// an unknown name (the message lists the known ones), an empty cycle for
// polled/fixed, a slot with src < 1 or seconds <= 0, slot fields given to
// auto_discovery, non-positive slot_seconds, coolness 0 or expire_cycles 0
// or an unknown blank_rule for auto_discovery, own id < 1 for fixed/auto_discovery, a non-finite
// epoch, or a fixed cycle longer than a day without an epoch (it could not
// realign at midnight).
//
// Thread-safe: keeps no state; the Mac it builds lives on the core thread that
// drives `scheduler` (mac.h).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "core/scheduler.h"
#include "mac/mac.h"

namespace acomms::mac {

// "auto_discovery", "fixed", "none", "polled".
std::vector<std::string> mac_names();

// The configured slots as a Cycle (DATA slots; dest -1 when unset).
Cycle cycle_from_config(const v1::MacConfig& config);

std::unique_ptr<Mac> make_mac(const v1::MacConfig& config, int32_t own_id,
                              core::Scheduler& scheduler);

}  // namespace acomms::mac
