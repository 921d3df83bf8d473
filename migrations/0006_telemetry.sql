-- Position telemetry (daemon/telemetry): what each end of a stream keeps so
-- that a daemon killed at any moment continues the stream, and the track a
-- receiver reconstructed (acommsctl track).
--
-- A sender's row is written in the same store queue as, and after, the
-- message it describes: the stored state is never ahead of the queue, and
-- at start a stream continues after the newest sequence still queued
-- (telemetry/stream_sender.h).
CREATE TABLE telemetry_sender (
  receiver INTEGER PRIMARY KEY NOT NULL,  -- modem id
  state BLOB NOT NULL
);

-- A receiver's rows are written after the received events they consumed;
-- received events newer than telemetry_progress.last_seq are replayed from
-- the event log at start (telemetry/telemetry_node.h).
CREATE TABLE telemetry_receiver (
  sender INTEGER PRIMARY KEY NOT NULL,  -- modem id
  state BLOB NOT NULL
);

CREATE TABLE telemetry_progress (
  name TEXT PRIMARY KEY NOT NULL,
  last_seq INTEGER NOT NULL
) WITHOUT ROWID;
INSERT INTO telemetry_progress (name, last_seq) VALUES ('received', 0);

-- One row per reconstructed sample: local metres from the datum, z up.
CREATE TABLE telemetry_position (
  src INTEGER NOT NULL,
  time REAL NOT NULL,
  x REAL NOT NULL,
  y REAL NOT NULL,
  z REAL NOT NULL,
  full INTEGER NOT NULL,
  PRIMARY KEY (src, time)
) WITHOUT ROWID;
