#pragma once
// What one end of a telemetry stream must remember to stay in step across a
// restart: the predictor's state right after the last full transmission
// (StreamPredictor::save: the observer's and the model's statistics, which
// outlive fulls) and the samples since that full.
//
// Replaying the samples (at most full_every of them) on top of the state at
// the full rebuilds the predictor exactly, and gives the state before the
// last delta too (a resent delta is read with it). The bytes carry the
// config's fingerprint: state saved under another config, or by an earlier
// layout, is refused, and the end starts over (the sender with a fresh full,
// the receiver waiting for one).

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
  std::string at_full;  // StreamPredictor::save() after the full (when in_step)
};

std::string serialize(const StreamHistory& history, uint64_t config_fingerprint);

// nullopt when the bytes are malformed or were saved under another config.
std::optional<StreamHistory> parse_history(std::string_view bytes, uint64_t config_fingerprint);

}  // namespace acomms::telemetry
