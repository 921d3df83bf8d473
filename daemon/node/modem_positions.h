#pragma once
// Where the other modems are, as far as this node knows: the newest
// position each node's telemetry gave (acomms.telemetry.Position, the
// telemetry datum's local metres, z up), by node id, which is its modem id.
//
// Why: the model's prediction for a packet heard from a real modem
// (node/link_prediction.h) needs the sender's position at that moment, and
// on a real network the only live source of it is the sender's telemetry.
// A position is kept with its time, so a reader can refuse a stale one.
// Core thread only (written where telemetry publishes, read by the links).

#include <cstdint>
#include <map>
#include <optional>

#include "core/node_position.h"

namespace acomms::node {

class ModemPositions {
 public:
  void set(int32_t modem, const core::NodeFix& fix) {
    auto [it, added] = latest_.try_emplace(modem, fix);
    if (!added && fix.time_s >= it->second.time_s) it->second = fix;
  }
  std::optional<core::NodeFix> latest(int32_t modem) const {
    auto it = latest_.find(modem);
    if (it == latest_.end()) return std::nullopt;
    return it->second;
  }

 private:
  std::map<int32_t, core::NodeFix> latest_;
};

}  // namespace acomms::node
