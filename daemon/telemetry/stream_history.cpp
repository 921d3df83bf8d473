#include "telemetry/stream_history.h"

#include "util/little_endian.h"

namespace acomms::telemetry {
namespace {

constexpr uint8_t kVersion = 2;  // 2: at_full
constexpr size_t kMaxSamples = 10002;  // full_every <= 10000, plus the full

}  // namespace

// Layout, little-endian: version (1), fingerprint (8), in_step (1),
// sequence (1), time_s (8), count (4), then count x 3 x int64 positions,
// then at_full's size (4) and bytes.
std::string serialize(const StreamHistory& history, uint64_t config_fingerprint) {
  std::string out;
  util::put_le(&out, kVersion, 1);
  util::put_le(&out, config_fingerprint, 8);
  util::put_le(&out, history.in_step ? 1 : 0, 1);
  util::put_le(&out, history.sequence, 1);
  util::put_le(&out, static_cast<uint64_t>(history.time_s), 8);
  util::put_le(&out, history.since_full.size(), 4);
  for (const GridPosition& position : history.since_full)
    for (int64_t v : position) util::put_le(&out, static_cast<uint64_t>(v), 8);
  util::put_le(&out, history.at_full.size(), 4);
  out.append(history.at_full);
  return out;
}

std::optional<StreamHistory> parse_history(std::string_view in, uint64_t config_fingerprint) {
  uint64_t version, fingerprint, in_step, sequence, time, count;
  if (!util::take_le(&in, 1, &version) || version != kVersion) return std::nullopt;
  if (!util::take_le(&in, 8, &fingerprint) || fingerprint != config_fingerprint) return std::nullopt;
  if (!util::take_le(&in, 1, &in_step) || in_step > 1) return std::nullopt;
  if (!util::take_le(&in, 1, &sequence) || !util::take_le(&in, 8, &time) || !util::take_le(&in, 4, &count)) {
    return std::nullopt;
  }
  if (count > kMaxSamples || in.size() < count * 3 * 8 + 4) return std::nullopt;
  if ((in_step == 1) != (count > 0)) return std::nullopt;
  StreamHistory history;
  history.in_step = in_step == 1;
  history.sequence = static_cast<uint32_t>(sequence);
  history.time_s = static_cast<int64_t>(time);
  history.since_full.resize(count);
  for (GridPosition& position : history.since_full) {
    for (int64_t& v : position) {
      uint64_t raw = 0;
      util::take_le(&in, 8, &raw);
      v = static_cast<int64_t>(raw);
    }
  }
  uint64_t size = 0;
  if (!util::take_le(&in, 4, &size) || in.size() != size) return std::nullopt;
  history.at_full.assign(in);
  return history;
}

}  // namespace acomms::telemetry
