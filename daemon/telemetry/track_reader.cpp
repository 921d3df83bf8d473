#include "telemetry/track_reader.h"

namespace acomms::telemetry {

TrackReader::TrackReader(const std::string& store_path) : db_(store_path, store::Database::Mode::kReadOnly) {}

TrackPage TrackReader::track(int32_t src, double since_s, size_t limit) {
  std::lock_guard lock(mutex_);
  store::Statement query = db_.prepare(
      "SELECT time, x, y, z, full FROM telemetry_position WHERE src = ? AND time >= ? ORDER BY time LIMIT ?");
  query.bind(1, int64_t{src}).bind_double(2, since_s).bind(3, static_cast<int64_t>(limit + 1));
  TrackPage page;
  while (query.step()) {
    if (page.positions.size() == limit) {
      page.truncated = true;
      break;
    }
    ReceivedPosition p;
    p.src = src;
    p.time_s = static_cast<int64_t>(query.column_double(0));
    p.position_m = {query.column_double(1), query.column_double(2), query.column_double(3)};
    p.full = query.column_int64(4) != 0;
    page.positions.push_back(p);
  }
  return page;
}

}  // namespace acomms::telemetry
