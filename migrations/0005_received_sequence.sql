-- A durable sequence number for every received message, so that a
-- subscriber can say "everything after N" and miss nothing across its own
-- reconnects and the daemon's restarts (Subscribe's `after`).
--
-- event_log.id is a plain rowid: it would be handed out again once the
-- newest rows are pruned. The sequence is therefore kept apart, in
-- event_sequence, which only ever grows and which pruning never touches:
-- a number, once a subscriber has seen it, names one message forever.
-- NULL on every event that is not a "received" one.
ALTER TABLE event_log ADD COLUMN seq INTEGER;

-- Replay reads "received events after N, in order": the seq index answers
-- it alone. Partial, so the other kinds of events cost it nothing.
CREATE UNIQUE INDEX event_log_by_seq ON event_log (seq) WHERE seq IS NOT NULL;

-- The last number handed out, per sequence (only 'received' so far). Written
-- in the transaction that logs the event carrying the number.
CREATE TABLE event_sequence (
  name TEXT PRIMARY KEY NOT NULL,
  last INTEGER NOT NULL
) WITHOUT ROWID;

INSERT INTO event_sequence (name, last)
  VALUES ('received', (SELECT COUNT(*) FROM event_log WHERE kind = 'received'));
