#include "store/migration.h"

#include <charconv>

#include "store/sqlite.h"

namespace acomms::store {

// Defined in the generated file that embeds migrations/*.sql.
const std::vector<std::pair<std::string_view, std::string_view>>& embedded_migration_files();

namespace {

constexpr std::string_view kCreateSchemaTable = R"sql(
CREATE TABLE IF NOT EXISTS schema_migrations (
  version    INTEGER PRIMARY KEY NOT NULL,
  name       TEXT NOT NULL,
  applied_at TEXT NOT NULL
))sql";

std::vector<Migration> parse_embedded() {
  std::vector<Migration> migrations;
  for (const auto& [name, sql] : embedded_migration_files()) {
    int64_t version = 0;
    auto [end, ec] = std::from_chars(name.data(), name.data() + 4, version);
    if (ec != std::errc() || end != name.data() + 4 || version <= 0) {
      throw StoreError("migration file name " + std::string(name) + " does not start with NNNN_");
    }
    if (!migrations.empty() && migrations.back().version >= version) {
      throw StoreError("migration " + std::string(name) + " repeats or goes back in version");
    }
    migrations.push_back({version, std::string(name), sql});
  }
  return migrations;
}

}  // namespace

const std::vector<Migration>& known_migrations() {
  static const std::vector<Migration> migrations = parse_embedded();
  return migrations;
}

int64_t schema_version(Database& db) {
  db.exec(kCreateSchemaTable);
  Statement query = db.prepare("SELECT coalesce(max(version), 0) FROM schema_migrations");
  query.step();
  return query.column_int64(0);
}

MigrationReport migrate(Database& db, const std::vector<Migration>& migrations) {
  MigrationReport report;
  // IMMEDIATE takes the write lock before reading the version, so two
  // processes starting on one store cannot both apply the same migration.
  db.exec("BEGIN IMMEDIATE");
  try {
    report.from_version = schema_version(db);
    int64_t newest = migrations.empty() ? 0 : migrations.back().version;
    if (report.from_version > newest) {
      throw StoreError("store " + db.path() + " has schema version " +
                       std::to_string(report.from_version) + ", newer than this acommsd knows (" +
                       std::to_string(newest) +
                       "): it was written by a newer acommsd. Run that release, or use another "
                       "data dir; the store was left untouched");
    }
    Statement record = db.prepare(
        "INSERT INTO schema_migrations (version, name, applied_at) "
        "VALUES (?, ?, strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))");
    for (const Migration& migration : migrations) {
      if (migration.version <= report.from_version) continue;
      try {
        db.exec(migration.sql);
      } catch (const StoreError& e) {
        throw StoreError("migration " + migration.name + " failed: " + e.what());
      }
      record.reset();
      record.bind(1, migration.version).bind(2, migration.name).step();
      ++report.applied;
    }
    report.to_version = std::max(report.from_version, newest);
    db.exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  return report;
}

}  // namespace acomms::store
