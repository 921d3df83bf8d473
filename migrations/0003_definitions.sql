-- DCCL definitions loaded through the API (LoadDefinitions), so that they
-- load again at start-up: queued messages of those types must find their
-- type after a restart. Definitions from the config are not listed here.
CREATE TABLE loaded_definitions (
  id           INTEGER PRIMARY KEY,       -- load order
  path         TEXT NOT NULL,             -- as given to the codec: a disk path, or a
                                          -- name relative to the first include dir
  include_dirs TEXT NOT NULL DEFAULT '',  -- newline-separated
  UNIQUE (path, include_dirs)
);
