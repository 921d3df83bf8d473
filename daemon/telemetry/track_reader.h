#pragma once
// Reads the positions a receiver reconstructed (telemetry_position) for the
// Track API and for Subscribe's replay, on its own read-only connection: WAL lets it read while the
// store writer appends, so `acommsctl track` never delays the link.
//
// Thread-safe (one connection under a mutex).

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "store/sqlite.h"
#include "telemetry/stream_receiver.h"

namespace acomms::telemetry {

struct TrackPage {
  std::vector<ReceivedPosition> positions;  // oldest first
  bool truncated = false;
};

class TrackReader {
 public:
  // Throws StoreError.
  explicit TrackReader(const std::string& store_path);

  // Positions from `src` with time >= since_s, oldest first, at most limit.
  TrackPage track(int32_t src, double since_s, size_t limit);
  // Positions numbered in the received sequence (ReceivedPosition::seq)
  // after `after`, from `src` (unset: any), in seq order, at most `limit`:
  // Subscribe's replay. Positions stored before migration 0010 have no
  // number and are not among them.
  std::vector<ReceivedPosition> positions_after(int64_t after, std::optional<int32_t> src, size_t limit);

 private:
  std::mutex mutex_;
  store::Database db_;
};

}  // namespace acomms::telemetry
