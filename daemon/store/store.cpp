#include "store/store.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <spdlog/spdlog.h>

namespace acomms::store {
namespace {

std::string errno_text() { return std::strerror(errno); }

void make_data_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw StoreError("data dir " + dir + ": cannot create: " + ec.message());
  if (!std::filesystem::is_directory(dir, ec)) {
    throw StoreError("data dir " + dir + ": exists and is not a directory");
  }
}

// An advisory lock on <dir>/acommsd.lock, held while the Store lives. It goes
// away by itself when the process dies, so a crash never leaves a stale lock.
int lock_data_dir(const std::string& dir) {
  std::string path = dir + "/acommsd.lock";
  int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0640);
  if (fd < 0) throw StoreError("data dir " + dir + ": cannot create lock file: " + errno_text());
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    int error = errno;
    ::close(fd);
    if (error == EWOULDBLOCK) {
      throw StoreError("data dir " + dir + " is in use by another acommsd");
    }
    throw StoreError("data dir " + dir + ": cannot lock: " + std::strerror(error));
  }
  return fd;
}

std::string single_text(Database& db, const char* sql) {
  Statement statement = db.prepare(sql);
  return statement.step() ? statement.column_text(0) : std::string();
}

}  // namespace

Store::Store(const std::string& data_dir, const Options& options) : data_dir_(data_dir) {
  make_data_dir(data_dir_);
  lock_fd_ = lock_data_dir(data_dir_);
  std::string path = data_dir_ + "/" + kStoreFileName;
  try {
    db_ = std::make_unique<Database>(path, Database::Mode::kReadWrite, options.vfs);
    // SQLite quietly opens a write-protected file read-only; a daemon that
    // cannot write would only fail at the first Submit, so refuse now.
    if (sqlite3_db_readonly(db_->handle(), "main") == 1) {
      throw StoreError("store " + path +
                       " is read-only: check that the data dir and the file are writable by this user");
    }
    // The first real read is where SQLite finds out whether the file is a
    // database at all; word the error for the operator, not for SQLite.
    std::string mode;
    try {
      mode = single_text(*db_, "PRAGMA journal_mode=WAL");
    } catch (const StoreError& e) {
      throw StoreError("store " + path + " is not a usable SQLite database (" + e.what() +
                       "): move it aside to start empty, or restore a backup");
    }
    if (mode != "wal") {
      throw StoreError("store " + path + ": cannot switch to WAL mode (got '" + mode +
                       "'): is the data dir on a filesystem without shared-memory support?");
    }
    // FULL: a commit is on disk before a Submit is answered, even across a
    // power loss, not just a process crash.
    db_->exec("PRAGMA synchronous=FULL; PRAGMA foreign_keys=ON");
    std::string check = single_text(*db_, "PRAGMA quick_check");
    if (check != "ok") {
      throw StoreError("store " + path + " is corrupt (" + check +
                       "): move it aside to start empty, or restore a backup");
    }
    migration_ = migrate(*db_, known_migrations());
  } catch (const StoreError& e) {
    db_.reset();
    ::close(lock_fd_);
    std::string text = e.what();
    // SQLite says "attempt to write a readonly database"; say what to fix.
    if (text.find("readonly") != std::string::npos || text.find("unable to open") != std::string::npos) {
      throw StoreError(text + " (check that the data dir and " + std::string(kStoreFileName) +
                       " are writable by this user)");
    }
    throw;
  }
  spdlog::info("store: {} at schema version {} ({} migration{} applied)", path,
               migration_.to_version, migration_.applied, migration_.applied == 1 ? "" : "s");
}

Store::~Store() {
  if (db_) {
    try {
      db_->exec("PRAGMA wal_checkpoint(TRUNCATE)");
    } catch (const StoreError& e) {
      spdlog::warn("store: checkpoint at close failed: {}", e.what());
    }
    db_.reset();
  }
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

}  // namespace acomms::store
