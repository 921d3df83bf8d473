-- Messages of authenticated types (config auth.type, README "Authenticated
-- types") accepted from the link: a receiver refuses the same bytes again
-- as a replay, also after its own restart, so what it accepted must be on
-- disk before the message reaches a subscriber. Written in the transaction
-- of the message's "received" event; rows stamped longer ago than the
-- longest authenticated window are deleted as new ones come (a replay of
-- them is refused as stale instead).
--
-- encoded: the message's bytes as received, trailer (key id, send time,
-- counter, tag) included; sent_s: the send time of its trailer, Unix
-- seconds.
CREATE TABLE auth_accepted (
  type TEXT NOT NULL,
  encoded BLOB NOT NULL,
  sent_s INTEGER NOT NULL,
  PRIMARY KEY (type, encoded)
) WITHOUT ROWID;
CREATE INDEX auth_accepted_by_sent ON auth_accepted (sent_s);
