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

std::vector<ReceivedPosition> TrackReader::positions_after(int64_t after, std::optional<int32_t> src,
                                                           size_t limit) {
  std::string sql =
      "SELECT seq, src, time, x, y, z, full, received FROM telemetry_position WHERE seq > ?";
  if (src) sql += " AND src = ?";
  sql += " ORDER BY seq LIMIT ?";  // telemetry_position_by_seq: no sort
  std::lock_guard lock(mutex_);
  store::Statement query = db_.prepare(sql);
  int index = 1;
  query.bind(index++, after);
  if (src) query.bind(index++, int64_t{*src});
  query.bind(index++, static_cast<int64_t>(limit));
  std::vector<ReceivedPosition> out;
  while (query.step()) {
    ReceivedPosition& p = out.emplace_back();
    p.seq = query.column_int64(0);
    p.src = static_cast<int32_t>(query.column_int64(1));
    p.time_s = static_cast<int64_t>(query.column_double(2));
    p.position_m = {query.column_double(3), query.column_double(4), query.column_double(5)};
    p.full = query.column_int64(6) != 0;
    p.received_s = query.is_null(7) ? 0 : query.column_double(7);
  }
  return out;
}

}  // namespace acomms::telemetry
