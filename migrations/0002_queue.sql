-- The message journal (daemon/queue/sqlite_journal.h): every message a
-- Submit acknowledged, until an event ends its life, and the event log.

-- One row per message still in a queue. A row is deleted in the same
-- transaction that logs the event removing it (acked, expired, dropped), so
-- after a crash the rows are exactly the messages still owed to the link.
--
-- AUTOINCREMENT, not a plain rowid: clients see these ids and acks refer to
-- them, so an id must never be handed out twice, not even after the highest
-- message was removed and the daemon restarted (a plain rowid would reuse it).
-- No secondary index: the only read is load() at start-up, in id order.
CREATE TABLE queued_messages (
  id           INTEGER PRIMARY KEY AUTOINCREMENT,
  type         TEXT    NOT NULL,           -- DCCL full type name
  payload      BLOB    NOT NULL,           -- the protobuf message, serialized
  src          INTEGER NOT NULL,           -- modem id, -1 if none
  dest         INTEGER NOT NULL,           -- modem id, 0 = broadcast
  submitted_at REAL    NOT NULL,           -- Clock seconds since the Unix epoch
  ttl_s        REAL    NOT NULL DEFAULT 0  -- 0 = the queue's own ttl
);

-- What happened to messages, so that none ever disappears silently. Only
-- appended to while the daemon runs; read by people and tools.
-- "None" is stored as NULL, not as the in-memory sentinels (message_id 0,
-- frame_id 0, modem id -1), so queries need no magic numbers.
CREATE TABLE event_log (
  id         INTEGER PRIMARY KEY,
  time       REAL    NOT NULL,              -- Clock seconds since the Unix epoch
  kind       TEXT    NOT NULL,              -- to_string(QueueEventKind): queued, sent, acked, ...
  type       TEXT    NOT NULL,              -- DCCL message type
  message_id INTEGER,                       -- queued_messages.id (no foreign key: the
                                            -- message row is deleted, its history stays)
  frame_id   INTEGER,
  src        INTEGER,
  dest       INTEGER,
  detail     TEXT    NOT NULL DEFAULT ''    -- human-readable reason
);

-- "What happened between t0 and t1", and pruning the oldest events.
CREATE INDEX event_log_by_time ON event_log (time);
-- "What happened to messages of this type (lately)": the type column first
-- answers by-type queries alone, time second keeps them ordered by time.
-- Each index costs every Submit a b-tree write, so there are only these two;
-- a message's history is rare enough to scan for.
CREATE INDEX event_log_by_type_time ON event_log (type, time);
