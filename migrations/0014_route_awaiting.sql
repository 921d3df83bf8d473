-- A gateway origin's notes of its routed messages that await their
-- end-to-end ack (route/end_to_end_ack.h): one per sequence (the message's
-- journal id mod 65536), written as it is sent wrapped, marked when its
-- first hop ACKs it, deleted when its receipt (end-to-end ack or expiry
-- report) comes. A receipt that arrives after a restart (a SIGKILL
-- included) is then still attached to its message. A row is forgotten at
-- forget_after (Unix seconds: sent_at plus the message's remaining ttl,
-- the receipt's own ttl and a margin: no receipt can come later); at most
-- 65536 rows (the sequence is the key; a wrapped sequence replaces its
-- row), and the forwarder keeps at most 4096.
CREATE TABLE route_awaiting (
  seq          INTEGER PRIMARY KEY,
  message_id   INTEGER NOT NULL,
  type         TEXT    NOT NULL,
  dest         INTEGER NOT NULL,
  next_hop     INTEGER NOT NULL,
  sent_at      REAL    NOT NULL,
  hop_acked    INTEGER NOT NULL,
  forget_after REAL    NOT NULL
);
