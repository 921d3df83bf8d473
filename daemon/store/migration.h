#pragma once
// Schema migrations: numbered SQL files (migrations/NNNN_name.sql), compiled
// into the binary, applied in order inside one transaction, each recorded in
// the schema_migrations table. A landed migration is never edited, so the
// version number alone says what a database contains.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace acomms::store {

class Database;

struct Migration {
  int64_t version;   // NNNN
  std::string name;  // file name, e.g. "0001_initial.sql"
  std::string_view sql;
};

// The migrations this build knows, in ascending version order.
const std::vector<Migration>& known_migrations();

struct MigrationReport {
  int64_t from_version = 0;  // 0: a new store
  int64_t to_version = 0;
  int applied = 0;
};

// Brings `db` up to the newest of `migrations`. Throws StoreError when the
// store was written by a newer schema (it is never downgraded or touched) or a
// migration fails (nothing of the failed run is kept).
MigrationReport migrate(Database& db, const std::vector<Migration>& migrations);

// Highest applied version, 0 for a store without migrations.
int64_t schema_version(Database& db);

}  // namespace acomms::store
