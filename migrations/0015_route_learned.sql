-- A gateway's routes learned from traffic (route/route_table.h): one per
-- destination (at most 65535 rows), with where it came from ('heard': the
-- node itself was heard on the link; 'relayed': its messages came through
-- next_hop) and when it was last confirmed (Unix seconds). Read back at
-- start, so that a restarted gateway still knows where its vehicles are;
-- the clock is the wall clock, so a route ages while the node is down and
-- one older than routing.learned_max_age_s comes back stale (listed, not
-- used). Written when the route changes and at most every 30 s while it
-- is only confirmed again: a stored time is never later than the real one.
CREATE TABLE route_learned (
  dest           INTEGER PRIMARY KEY,
  next_hop       INTEGER NOT NULL,
  link           TEXT    NOT NULL,
  source         TEXT    NOT NULL,
  last_confirmed REAL    NOT NULL
);
