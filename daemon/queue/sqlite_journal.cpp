#include "queue/sqlite_journal.h"

#include <spdlog/spdlog.h>

#include <exception>
#include <string>

namespace acomms::queue {
namespace {

using store::Database;
using store::Statement;

constexpr std::string_view kInsertMessage =
    "INSERT INTO queued_messages (type, payload, src, dest, submitted_at, ttl_s, sealed) "
    "VALUES (?, ?, ?, ?, ?, ?, ?)";
constexpr std::string_view kInsertEvent =
    "INSERT INTO event_log (time, kind, type, message_id, frame_id, src, dest, detail, encoded, seq, "
    "link_figures) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)";
// MAX: the counter never goes back, whatever order numbers arrive in.
constexpr std::string_view kAdvanceReceivedSeq =
    "UPDATE event_sequence SET last = MAX(last, ?) WHERE name = 'received'";
constexpr std::string_view kLastReceivedSeq = "SELECT last FROM event_sequence WHERE name = 'received'";
constexpr std::string_view kDeleteMessage = "DELETE FROM queued_messages WHERE id = ?";
constexpr std::string_view kLoadMessages =
    "SELECT id, type, payload, src, dest, submitted_at, ttl_s, sealed FROM queued_messages ORDER BY id";
// By time first, so that event_log_by_time finds the window.
constexpr std::string_view kLoadReceived =
    "SELECT time, type, src, dest, encoded FROM event_log "
    "WHERE time >= ? AND kind = 'received' AND encoded IS NOT NULL ORDER BY time, id";

// OR IGNORE: the same bytes accepted twice cannot happen (the AuthGuard
// refuses the second), but a row must never fail an event's transaction.
constexpr std::string_view kInsertAuthAccepted =
    "INSERT OR IGNORE INTO auth_accepted (type, src, encoded, sent_s) VALUES (?, ?, ?, ?)";
constexpr std::string_view kForgetAuthAccepted = "DELETE FROM auth_accepted WHERE sent_s < ?";
constexpr std::string_view kLoadAuthAccepted =
    "SELECT type, encoded, sent_s, src FROM auth_accepted WHERE sent_s >= ? ORDER BY sent_s";
// INSERT OR REPLACE: a sequence seen again after its origin wrapped is a new
// message, kept until its own time.
constexpr std::string_view kInsertRouted =
    "INSERT OR REPLACE INTO route_delivered (origin, seq, forget_after) VALUES (?, ?, ?)";
constexpr std::string_view kForgetRouted = "DELETE FROM route_delivered WHERE forget_after < ?";
constexpr std::string_view kLoadRouted =
    "SELECT origin, seq, forget_after FROM route_delivered WHERE forget_after >= ? ORDER BY forget_after";

// A cached statement left mid-step would hold the batch open; reset it
// whichever way the work ends.
class ResetOnExit {
 public:
  explicit ResetOnExit(Statement& statement) : statement_(statement) {}
  ~ResetOnExit() { statement_.reset(); }
  ResetOnExit(const ResetOnExit&) = delete;
  ResetOnExit& operator=(const ResetOnExit&) = delete;

 private:
  Statement& statement_;
};

// event_log stores "none" as NULL rather than the in-memory sentinels.
void bind_or_null(Statement& statement, int index, int64_t value, int64_t none) {
  if (value == none) {
    statement.bind_null(index);
  } else {
    statement.bind(index, value);
  }
}

}  // namespace

void SqliteJournal::append(JournalMessage message, Appended appended) {
  // Set by the work inside the transaction, reported only after the commit:
  // an id must not reach a client before its message is durable.
  auto id = std::make_shared<int64_t>(0);
  writer_.post(
      [this, id, message = std::move(message)](Database& db) mutable {
        Statement& insert = writer_.prepared(kInsertMessage);
        ResetOnExit reset(insert);
        insert.bind(1, message.type)
            .bind_blob(2, message.payload)
            .bind(3, int64_t{message.src})
            .bind(4, int64_t{message.dest})
            .bind_double(5, message.submitted_at)
            .bind_double(6, message.ttl_s);
        if (message.sealed.empty()) {
          insert.bind_null(7);
        } else {
          insert.bind_blob(7, message.sealed);
        }
        insert.step();
        message.id = static_cast<int64_t>(sqlite3_last_insert_rowid(db.handle()));
        // Its "queued" event rides in the same commit.
        write_event(queued_event(message));
        *id = message.id;
      },
      [id, appended = std::move(appended)](std::exception_ptr error) {
        appended(error ? 0 : *id, error);
      });
}

void SqliteJournal::record(const QueueEvent& event) {
  // The core has already acted on the event; if its commit fails there is
  // nobody to answer, so the log must say what the store now lacks. For an
  // event that removes a message, the store keeps the row the queue has
  // forgotten: at the next start that message is queued (and sent) again.
  writer_.post([this, event](Database&) { write_event(event); },
               [this, kind = event.kind, type = event.type, id = event.message_id,
                removes = event.removes_message](std::exception_ptr error) {
                 if (!error) return;
                 ++events_not_stored_;
                 std::string why;
                 try {
                   std::rethrow_exception(error);
                 } catch (const std::exception& e) {
                   why = e.what();
                 } catch (...) {
                   why = "unknown failure";
                 }
                 spdlog::error("journal: {} event of {} message {} not logged: {}{}", to_string(kind), type, id, why,
                               removes && id != 0 ? "; the store still holds the message, which will be queued "
                                                    "again at the next start"
                                                  : "");
               });
}

// On the writer thread, inside the request's savepoint.
void SqliteJournal::write_event(const QueueEvent& event) {
  Statement& insert = writer_.prepared(kInsertEvent);
  ResetOnExit reset_insert(insert);
  insert.bind_double(1, event.time).bind(2, to_string(event.kind)).bind(3, event.type);
  bind_or_null(insert, 4, event.message_id, 0);
  // Frame ids are unsigned; SQLite integers are signed 64-bit. The bits are
  // kept: ids past 2^63 read back negative, but stay distinct.
  bind_or_null(insert, 5, static_cast<int64_t>(event.frame_id), 0);
  bind_or_null(insert, 6, event.src, -1);
  bind_or_null(insert, 7, event.dest, -1);
  insert.bind(8, event.detail);
  if (event.encoded.empty()) {
    insert.bind_null(9);
  } else {
    insert.bind_blob(9, event.encoded);
  }
  bind_or_null(insert, 10, event.seq, 0);
  // An empty string is figures with every field at its default: a
  // zero-length blob, not NULL (none).
  if (event.link_figures) {
    insert.bind_blob(11, *event.link_figures);
  } else {
    insert.bind_null(11);
  }
  insert.step();
  if (event.seq != 0) {
    // The number and its event are durable together: after a crash the
    // counter is past every number a subscriber can have seen.
    Statement& advance = writer_.prepared(kAdvanceReceivedSeq);
    ResetOnExit reset_advance(advance);
    advance.bind(1, event.seq);
    advance.step();
  }
  if (event.auth_sent_s) {
    // With its received event: a message published is one a replay of
    // which will be recognised, even after a crash.
    Statement& accepted = writer_.prepared(kInsertAuthAccepted);
    ResetOnExit reset_accepted(accepted);
    accepted.bind(1, event.type);
    if (event.auth_sender) {
      accepted.bind(2, int64_t{*event.auth_sender});
    } else {
      accepted.bind_null(2);
    }
    accepted.bind_blob(3, event.encoded).bind(4, int64_t{*event.auth_sent_s});
    accepted.step();
    Statement& forget = writer_.prepared(kForgetAuthAccepted);
    ResetOnExit reset_forget(forget);
    forget.bind_double(1, event.auth_forget_before);
    forget.step();
  }
  if (event.routed) {
    // With its received event, as auth_accepted: delivered and known as
    // delivered are durable together.
    Statement& routed = writer_.prepared(kInsertRouted);
    ResetOnExit reset_routed(routed);
    routed.bind(1, int64_t{event.routed->origin}).bind(2, int64_t{event.routed->seq});
    routed.bind_double(3, event.routed->forget_after);
    routed.step();
  }
  // Same savepoint, same transaction: the event and the removal are on disk
  // together or not at all.
  if (event.removes_message && event.message_id != 0) {
    Statement& remove = writer_.prepared(kDeleteMessage);
    ResetOnExit reset_remove(remove);
    remove.bind(1, event.message_id);
    remove.step();
  }
}

std::vector<JournalMessage> SqliteJournal::load() {
  // Through the writer too: it is the only thread allowed on the connection.
  return writer_
      .submit([](Database& db) {
        std::vector<JournalMessage> messages;
        Statement query = db.prepare(kLoadMessages);
        while (query.step()) {
          JournalMessage& m = messages.emplace_back();
          m.id = query.column_int64(0);
          m.type = query.column_text(1);
          m.payload = query.column_blob(2);
          m.src = static_cast<int32_t>(query.column_int64(3));
          m.dest = static_cast<int32_t>(query.column_int64(4));
          m.submitted_at = query.column_double(5);
          m.ttl_s = query.column_double(6);
          if (!query.is_null(7)) m.sealed = query.column_blob(7);
        }
        return messages;
      })
      .get();
}

std::vector<QueueEvent> SqliteJournal::received_since(double since) {
  return writer_
      .submit([since](Database& db) {
        std::vector<QueueEvent> events;
        Statement query = db.prepare(kLoadReceived);
        query.bind_double(1, since);
        while (query.step()) {
          QueueEvent& e = events.emplace_back();
          e.kind = QueueEventKind::kReceived;
          e.time = query.column_double(0);
          e.type = query.column_text(1);
          e.src = query.is_null(2) ? -1 : static_cast<int32_t>(query.column_int64(2));
          e.dest = query.is_null(3) ? -1 : static_cast<int32_t>(query.column_int64(3));
          e.encoded = query.column_blob(4);
        }
        return events;
      })
      .get();
}

std::vector<RoutedIdentity> SqliteJournal::routed_since(double now) {
  return writer_
      .submit([now](Database& db) {
        Statement forget = db.prepare(kForgetRouted);
        forget.bind_double(1, now);
        forget.step();
        std::vector<RoutedIdentity> out;
        Statement query = db.prepare(kLoadRouted);
        query.bind_double(1, now);
        while (query.step()) {
          RoutedIdentity& r = out.emplace_back();
          r.origin = static_cast<int32_t>(query.column_int64(0));
          r.seq = static_cast<int32_t>(query.column_int64(1));
          r.forget_after = query.column_double(2);
        }
        return out;
      })
      .get();
}

std::vector<QueueEvent> SqliteJournal::authenticated_since(double sent_since) {
  return writer_
      .submit([sent_since](Database& db) {
        std::vector<QueueEvent> events;
        Statement query = db.prepare(kLoadAuthAccepted);
        query.bind_double(1, sent_since);
        while (query.step()) {
          QueueEvent& e = events.emplace_back();
          e.kind = QueueEventKind::kReceived;
          e.type = query.column_text(0);
          e.encoded = query.column_blob(1);
          e.auth_sent_s = static_cast<uint32_t>(query.column_int64(2));
          if (!query.is_null(3)) e.auth_sender = static_cast<int32_t>(query.column_int64(3));
        }
        return events;
      })
      .get();
}

int64_t SqliteJournal::last_received_seq() {
  return writer_
      .submit([](Database& db) {
        Statement query = db.prepare(kLastReceivedSeq);
        return query.step() ? query.column_int64(0) : int64_t{0};
      })
      .get();
}

void SqliteJournal::when_committed(Committed committed) {
  // An empty request: its batch commits after every request queued before
  // it, and batches complete in order.
  writer_.post([](Database&) {}, std::move(committed));
}

void SqliteJournal::flush() { writer_.flush(); }

}  // namespace acomms::queue
