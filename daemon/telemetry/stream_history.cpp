#include "telemetry/stream_history.h"

namespace acomms::telemetry {
namespace {

constexpr uint8_t kVersion = 2;  // 2: at_full
constexpr size_t kMaxSamples = 10002;  // full_every <= 10000, plus the full

void put(std::string* out, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out->push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

bool get(std::string_view* in, int bytes, uint64_t* value) {
  if (in->size() < static_cast<size_t>(bytes)) return false;
  *value = 0;
  for (int i = 0; i < bytes; ++i) *value |= uint64_t{static_cast<uint8_t>((*in)[i])} << (8 * i);
  in->remove_prefix(static_cast<size_t>(bytes));
  return true;
}

}  // namespace

// Layout, little-endian: version (1), fingerprint (8), in_step (1),
// sequence (1), time_s (8), count (4), then count x 3 x int64 positions,
// then at_full's size (4) and bytes.
std::string serialize(const StreamHistory& history, uint64_t config_fingerprint) {
  std::string out;
  put(&out, kVersion, 1);
  put(&out, config_fingerprint, 8);
  put(&out, history.in_step ? 1 : 0, 1);
  put(&out, history.sequence, 1);
  put(&out, static_cast<uint64_t>(history.time_s), 8);
  put(&out, history.since_full.size(), 4);
  for (const GridPosition& position : history.since_full)
    for (int64_t v : position) put(&out, static_cast<uint64_t>(v), 8);
  put(&out, history.at_full.size(), 4);
  out.append(history.at_full);
  return out;
}

std::optional<StreamHistory> parse_history(std::string_view in, uint64_t config_fingerprint) {
  uint64_t version, fingerprint, in_step, sequence, time, count;
  if (!get(&in, 1, &version) || version != kVersion) return std::nullopt;
  if (!get(&in, 8, &fingerprint) || fingerprint != config_fingerprint) return std::nullopt;
  if (!get(&in, 1, &in_step) || in_step > 1) return std::nullopt;
  if (!get(&in, 1, &sequence) || !get(&in, 8, &time) || !get(&in, 4, &count)) return std::nullopt;
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
      get(&in, 8, &raw);
      v = static_cast<int64_t>(raw);
    }
  }
  uint64_t size = 0;
  if (!get(&in, 4, &size) || in.size() != size) return std::nullopt;
  history.at_full.assign(in);
  return history;
}

}  // namespace acomms::telemetry
