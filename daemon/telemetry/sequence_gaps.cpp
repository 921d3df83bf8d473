#include "telemetry/sequence_gaps.h"

#include "telemetry/wire_message.h"

namespace acomms::telemetry {

uint32_t SequenceGaps::observe(int32_t src, uint32_t sequence, bool fresh_start) {
  auto [it, first] = newest_.try_emplace(src, sequence);
  if (first) return 0;
  if (fresh_start) {
    ++counters_.restarts;
    it->second = sequence;
    return 0;
  }
  const int32_t d = sequence_distance(sequence, it->second);
  if (d <= 0) {
    ++counters_.late;
    return 0;
  }
  it->second = sequence;
  if (d - 1 > kMaxCounted) {
    ++counters_.jumps;
    return 0;
  }
  const auto missing = static_cast<uint32_t>(d - 1);
  counters_.missing += missing;
  return missing;
}

}  // namespace acomms::telemetry
