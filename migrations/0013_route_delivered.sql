-- Routed messages delivered at this node (route/forwarder.h): each is
-- known by its identity (origin, sequence) until forget_after (Unix
-- seconds: its remaining ttl when it arrived, plus a margin), written in
-- the transaction of its received event. A copy that comes by another path,
-- or a resend whose hop ACK was lost, after a restart (a SIGKILL included)
-- is then recognised and dropped instead of delivered twice. A sequence
-- that wrapped (2^16 messages from one origin) replaces its old row.
CREATE TABLE route_delivered (
  origin       INTEGER NOT NULL,
  seq          INTEGER NOT NULL,
  forget_after REAL    NOT NULL,
  PRIMARY KEY (origin, seq)
);
