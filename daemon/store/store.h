#pragma once
// The daemon's one SQLite file (<data dir>/acommsd.db), in WAL mode, migrated
// to this build's schema at open. The data dir is locked for the life of the
// Store so that two daemons never share one set of queues.
//
// Threads: open and close it on one thread, which may use db() until a
// GroupCommitWriter takes the connection; from then on only the writer's
// thread touches it (group_commit_writer.h).

#include <memory>
#include <string>

#include "store/migration.h"
#include "store/sqlite.h"

namespace acomms::store {

inline constexpr const char* kStoreFileName = "acommsd.db";

class Store {
 public:
  struct Options {
    // The registered sqlite3_vfs to open the file through; empty for the
    // default. For tests only (the fault-injecting VFS of tests/unit/store).
    std::string vfs;
  };

  // Creates the data dir if needed, opens and checks the database, applies
  // pending migrations. Throws StoreError with an actionable message when the
  // dir cannot be created or locked, or the file is unwritable, corrupt, or
  // from a newer schema.
  explicit Store(const std::string& data_dir) : Store(data_dir, Options()) {}
  Store(const std::string& data_dir, const Options& options);
  // Checkpoints the WAL into the main file and closes.
  ~Store();
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  Database& db() { return *db_; }
  const std::string& data_dir() const { return data_dir_; }
  int64_t schema_version() const { return migration_.to_version; }
  const MigrationReport& migration() const { return migration_; }

 private:
  std::string data_dir_;
  int lock_fd_ = -1;
  std::unique_ptr<Database> db_;
  MigrationReport migration_;
};

}  // namespace acomms::store
