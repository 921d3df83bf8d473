#include "queue/event_log_reader.h"

#include <algorithm>
#include <stdexcept>

namespace acomms::queue {
namespace {

constexpr QueueEventKind kAllKinds[] = {QueueEventKind::kQueued,  QueueEventKind::kSent,
                                        QueueEventKind::kAcked,   QueueEventKind::kExpired,
                                        QueueEventKind::kDropped, QueueEventKind::kRetry,
                                        QueueEventKind::kReceived, QueueEventKind::kPacket,
                                        QueueEventKind::kDelivered};

// "?, ?, ?" for an IN list of n values.
std::string placeholders(size_t n) {
  std::string out;
  for (size_t i = 0; i < n; ++i) out += i ? ", ?" : "?";
  return out;
}

// NULL (no figures: another kind of event, or a row older than migration
// 0008) stays apart from a zero-length blob (figures all at their defaults).
std::optional<std::string> link_figures_of(const store::Statement& statement, int column) {
  if (statement.is_null(column)) return std::nullopt;
  return statement.column_blob(column);
}

}  // namespace

QueueEventKind event_kind_from_string(const std::string& kind) {
  std::string known;
  for (QueueEventKind k : kAllKinds) {
    if (to_string(k) == kind) return k;
    known += (known.empty() ? "" : ", ") + std::string(to_string(k));
  }
  throw std::invalid_argument("unknown event kind \"" + kind + "\" (kinds: " + known + ")");
}

EventLogReader::EventLogReader(const std::string& store_path)
    : db_(store_path, store::Database::Mode::kReadOnly) {}

EventPage EventLogReader::query(const EventQuery& query) {
  for (const std::string& kind : query.kinds) (void)event_kind_from_string(kind);
  std::string sql =
      "SELECT id, time, kind, type, message_id, frame_id, src, dest, detail, link_figures FROM event_log WHERE 1";
  if (query.since > 0) sql += " AND time >= ?";
  if (query.until > 0) sql += " AND time <= ?";
  if (!query.kinds.empty()) sql += " AND kind IN (" + placeholders(query.kinds.size()) + ")";
  if (!query.types.empty()) sql += " AND type IN (" + placeholders(query.types.size()) + ")";
  if (query.message_id != 0) sql += " AND message_id = ?";
  // Newest first so LIMIT keeps the most recent; reversed below.
  sql += " ORDER BY time DESC, id DESC LIMIT ?";

  std::lock_guard lock(mutex_);
  store::Statement statement = db_.prepare(sql);
  int index = 1;
  if (query.since > 0) statement.bind_double(index++, query.since);
  if (query.until > 0) statement.bind_double(index++, query.until);
  for (const std::string& kind : query.kinds) statement.bind(index++, std::string_view(kind));
  for (const std::string& type : query.types) statement.bind(index++, std::string_view(type));
  if (query.message_id != 0) statement.bind(index++, query.message_id);
  statement.bind(index++, static_cast<int64_t>(query.limit + 1));

  EventPage page;
  while (statement.step()) {
    if (page.events.size() == query.limit) {
      page.truncated = true;
      break;
    }
    LoggedEvent logged;
    logged.id = statement.column_int64(0);
    QueueEvent& e = logged.event;
    e.time = statement.column_double(1);
    e.kind = event_kind_from_string(statement.column_text(2));
    e.type = statement.column_text(3);
    e.message_id = statement.is_null(4) ? 0 : statement.column_int64(4);
    e.frame_id = statement.is_null(5) ? 0 : static_cast<uint64_t>(statement.column_int64(5));
    e.src = statement.is_null(6) ? -1 : static_cast<int32_t>(statement.column_int64(6));
    e.dest = statement.is_null(7) ? -1 : static_cast<int32_t>(statement.column_int64(7));
    e.detail = statement.column_text(8);
    e.link_figures = link_figures_of(statement, 9);
    page.events.push_back(std::move(logged));
  }
  std::reverse(page.events.begin(), page.events.end());
  return page;
}

std::vector<StoredReceived> EventLogReader::received_after(int64_t after, const std::vector<std::string>& types,
                                                           std::optional<int32_t> src, size_t limit) {
  std::string sql =
      "SELECT seq, time, type, src, dest, encoded, link_figures FROM event_log "
      "WHERE seq > ? AND kind = 'received' AND encoded IS NOT NULL";
  if (!types.empty()) sql += " AND type IN (" + placeholders(types.size()) + ")";
  if (src) sql += " AND src = ?";
  sql += " ORDER BY seq LIMIT ?";  // event_log_by_seq: no sort

  std::lock_guard lock(mutex_);
  store::Statement statement = db_.prepare(sql);
  int index = 1;
  statement.bind(index++, after);
  for (const std::string& type : types) statement.bind(index++, std::string_view(type));
  if (src) statement.bind(index++, int64_t{*src});
  statement.bind(index++, static_cast<int64_t>(limit));
  std::vector<StoredReceived> out;
  while (statement.step()) {
    StoredReceived& r = out.emplace_back();
    r.seq = statement.column_int64(0);
    r.time = statement.column_double(1);
    r.type = statement.column_text(2);
    r.src = statement.is_null(3) ? -1 : static_cast<int32_t>(statement.column_int64(3));
    r.dest = statement.is_null(4) ? -1 : static_cast<int32_t>(statement.column_int64(4));
    r.encoded = statement.column_blob(5);
    r.link_figures = link_figures_of(statement, 6);
  }
  return out;
}

ReceivedRange EventLogReader::received_range() {
  std::lock_guard lock(mutex_);
  ReceivedRange range;
  // One read transaction, so that first and last agree with each other.
  db_.exec("BEGIN");
  try {
    store::Statement last = db_.prepare("SELECT last FROM event_sequence WHERE name = 'received'");
    if (last.step()) range.last = last.column_int64(0);
    store::Statement first = db_.prepare("SELECT MIN(seq) FROM event_log WHERE seq IS NOT NULL");
    range.first = (first.step() && !first.is_null(0)) ? first.column_int64(0) : range.last + 1;
  } catch (...) {
    db_.exec("ROLLBACK");
    throw;
  }
  db_.exec("COMMIT");
  return range;
}

}  // namespace acomms::queue
