-- The environment the vehicle knows (acomms.v1.Gram UpdateEnvironment):
-- the base as changed at run time and the CTD profile instances of the
-- window, so a restart does not forget the casts the vehicle took. One row,
-- the whole state as a serialized acomms.gram.KnownEnvironment: it is
-- small (a few profiles), always read and written whole, and its meaning
-- lives in the .proto, which evolves compatibly.
CREATE TABLE gram_environment (
  id INTEGER PRIMARY KEY CHECK (id = 1),
  state BLOB NOT NULL,
  updated_at REAL NOT NULL
);
