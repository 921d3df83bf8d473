#pragma once
// What one end of a telemetry stream must remember to stay in step across a
// restart: the samples since the last full transmission, not the observer's
// floating-point state.
//
// Observers and models restart at every full, so their state is a function
// of the full's position and the samples after it. Replaying those (at most
// full_every + 1 integer positions) rebuilds it exactly, on any build, which
// storing the Kalman filter's doubles would not promise across versions.
// The bytes carry the config's fingerprint: state saved under another config
// is refused, and the end starts over (the sender with a full).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "telemetry/observer.h"

namespace acomms::telemetry {

struct StreamHistory {
  bool in_step = false;   // a full was sent (received) since the start
  uint32_t sequence = 0;  // of the last message
  int64_t time_s = 0;     // of the last sample
  std::vector<GridPosition> since_full;  // [0]: the full's position
};

std::string serialize(const StreamHistory& history, uint64_t config_fingerprint);

// nullopt when the bytes are malformed or were saved under another config.
std::optional<StreamHistory> parse_history(std::string_view bytes, uint64_t config_fingerprint);

}  // namespace acomms::telemetry
