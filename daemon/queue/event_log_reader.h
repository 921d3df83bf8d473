#pragma once
// Reads the event log (what happened to messages) for the Events API, on
// its own read-only connection: WAL lets it read while the group-commit
// writer appends, so a query never delays a Submit.

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "queue/queue_event.h"
#include "store/sqlite.h"

namespace acomms::queue {

struct EventQuery {
  double since = 0;  // seconds since the Unix epoch; 0: unbounded
  double until = 0;
  std::vector<std::string> kinds;  // empty: all
  std::vector<std::string> types;  // empty: all
  int64_t message_id = 0;          // 0: any
  size_t limit = 1000;
};

struct LoggedEvent {
  int64_t id = 0;
  QueueEvent event;
};

struct EventPage {
  std::vector<LoggedEvent> events;  // oldest first
  bool truncated = false;           // more matched: these are the newest `limit`
};

class EventLogReader {
 public:
  // Opens `store_path` read-only. Throws StoreError.
  explicit EventLogReader(const std::string& store_path);

  // Any thread. Throws std::invalid_argument for an unknown kind, StoreError
  // if the store cannot be read.
  EventPage query(const EventQuery& query);

 private:
  std::mutex mutex_;  // the connection is NOMUTEX
  store::Database db_;
};

// "queued", "sent", ... as in the event log; throws std::invalid_argument
// listing the kinds for anything else.
QueueEventKind event_kind_from_string(const std::string& kind);

}  // namespace acomms::queue
