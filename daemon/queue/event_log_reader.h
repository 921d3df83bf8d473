#pragma once
// Reads the event log (what happened to messages) for the Events API, and
// the received messages Subscribe replays after a seq, on its own read-only
// connection: WAL lets it read while the group-commit writer appends, so a
// query never delays a Submit.
//
// Thread-safe: its one read-only connection is used under a mutex, so any
// thread may query.

#include <cstdint>
#include <mutex>
#include <optional>
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

// A received message as the store keeps it (for Subscribe's replay).
struct StoredReceived {
  int64_t seq = 0;
  double time = 0;
  std::string type;
  int32_t src = -1;
  int32_t dest = -1;
  std::string encoded;  // its DCCL bytes
  // The serialized acomms.v1.LinkFigures it arrived with (QueueEvent::link_figures).
  std::optional<std::string> link_figures;
};

// Which received sequence numbers the store can still replay.
struct ReceivedRange {
  int64_t first = 0;  // the oldest seq still held; last + 1 when none is
  int64_t last = 0;   // the newest seq handed out (0: none ever)

  // Whether "everything after `after`" can still be replayed whole: false
  // when some of it was pruned (Subscribe answers OUT_OF_RANGE).
  bool replayable_after(int64_t after) const { return after >= last || after + 1 >= first; }
};

class EventLogReader {
 public:
  // Opens `store_path` read-only. Throws StoreError.
  explicit EventLogReader(const std::string& store_path);

  // Any thread. Throws std::invalid_argument for an unknown kind, StoreError
  // if the store cannot be read.
  EventPage query(const EventQuery& query);

  // Any thread. Up to `limit` received messages with seq > `after`, of
  // `types` (empty: all) and from `src` (unset: anyone), in seq order.
  // Throws StoreError.
  std::vector<StoredReceived> received_after(int64_t after, const std::vector<std::string>& types,
                                             std::optional<int32_t> src, size_t limit);
  ReceivedRange received_range();

 private:
  std::mutex mutex_;  // the connection is NOMUTEX
  store::Database db_;
};

// "queued", "sent", ... as in the event log; throws std::invalid_argument
// listing the kinds for anything else.
QueueEventKind event_kind_from_string(const std::string& kind);

}  // namespace acomms::queue
