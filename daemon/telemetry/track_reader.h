#pragma once
// Reads the positions a receiver reconstructed (telemetry_position) for the
// Track API, on its own read-only connection: WAL lets it read while the
// store writer appends, so `acommsctl track` never delays the link.
//
// Thread-safe (one connection under a mutex).

#include <cstdint>
#include <mutex>
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

 private:
  std::mutex mutex_;
  store::Database db_;
};

}  // namespace acomms::telemetry
