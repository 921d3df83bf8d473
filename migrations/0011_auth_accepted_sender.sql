-- auth_accepted (0009) keyed by sender too: two nodes sealing the same
-- message in the same second make the same bytes (the fleet shares the
-- key), and the second must not be refused as a replay of the first. The
-- sender's id is covered by the tag (dccl/message_auth.h), so a recorded
-- message sent again under another id does not verify: keying by it opens
-- no gap for replays.
--
-- src: the transmission's source of the accepted message; NULL for rows
-- accepted before senders were told apart, which keep refusing their bytes
-- from any sender until they age out (they stay valid).
--
-- SQLite cannot change a primary key in place: the table is made again.
CREATE TABLE auth_accepted_by_sender (
  type TEXT NOT NULL,
  src INTEGER,
  encoded BLOB NOT NULL,
  sent_s INTEGER NOT NULL
);
INSERT INTO auth_accepted_by_sender (type, src, encoded, sent_s) SELECT type, NULL, encoded, sent_s FROM auth_accepted;
DROP TABLE auth_accepted;
ALTER TABLE auth_accepted_by_sender RENAME TO auth_accepted;
-- A NULL src is one value here (IFNULL), so that OR IGNORE still keeps one
-- row per message.
CREATE UNIQUE INDEX auth_accepted_key ON auth_accepted (type, IFNULL(src, -2147483648), encoded);
CREATE INDEX auth_accepted_by_sent ON auth_accepted (sent_s);
