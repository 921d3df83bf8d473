#include "store/sqlite.h"

namespace acomms::store {

Database::Database(const std::string& path, Mode mode, const std::string& vfs) : path_(path) {
  int flags = mode == Mode::kReadOnly ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
  int rc = sqlite3_open_v2(path.c_str(), &db_, flags | SQLITE_OPEN_NOMUTEX, vfs.empty() ? nullptr : vfs.c_str());
  if (rc != SQLITE_OK) {
    std::string reason = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close_v2(db_);
    db_ = nullptr;
    throw StoreError("cannot open store " + path + ": " + reason, rc);
  }
  sqlite3_extended_result_codes(db_, 1);
  // Another process (acommsctl reading, a backup) may briefly hold the lock.
  sqlite3_busy_timeout(db_, 5000);
}

Database::~Database() { sqlite3_close_v2(db_); }

void Database::exec(std::string_view sql) {
  char* error = nullptr;
  int rc = sqlite3_exec(db_, std::string(sql).c_str(), nullptr, nullptr, &error);
  if (rc != SQLITE_OK) {
    std::string reason = error ? error : sqlite3_errstr(rc);
    sqlite3_free(error);
    throw StoreError(path_ + ": " + reason, rc);
  }
}

Statement Database::prepare(std::string_view sql) { return Statement(*this, sql); }

std::string Database::last_error() const { return sqlite3_errmsg(db_); }

int Database::last_error_code() const { return sqlite3_extended_errcode(db_); }

Statement::Statement(Database& db, std::string_view sql) : db_(&db) {
  if (sqlite3_prepare_v2(db.handle(), sql.data(), static_cast<int>(sql.size()), &stmt_, nullptr) !=
      SQLITE_OK) {
    throw StoreError(db.path() + ": " + db.last_error(), db.last_error_code());
  }
}

Statement::~Statement() { sqlite3_finalize(stmt_); }

Statement::Statement(Statement&& other) noexcept : db_(other.db_), stmt_(other.stmt_) {
  other.stmt_ = nullptr;
}

Statement& Statement::bind(int index, int64_t value) {
  if (sqlite3_bind_int64(stmt_, index, value) != SQLITE_OK) {
    throw StoreError(db_->path() + ": " + db_->last_error(), db_->last_error_code());
  }
  return *this;
}

Statement& Statement::bind(int index, std::string_view text) {
  if (sqlite3_bind_text(stmt_, index, text.data(), static_cast<int>(text.size()),
                        SQLITE_TRANSIENT) != SQLITE_OK) {
    throw StoreError(db_->path() + ": " + db_->last_error(), db_->last_error_code());
  }
  return *this;
}

Statement& Statement::bind_double(int index, double value) {
  if (sqlite3_bind_double(stmt_, index, value) != SQLITE_OK) {
    throw StoreError(db_->path() + ": " + db_->last_error(), db_->last_error_code());
  }
  return *this;
}

Statement& Statement::bind_blob(int index, std::string_view bytes) {
  // A null pointer would bind SQL NULL; an empty payload is a zero-length blob.
  int rc = bytes.data() ? sqlite3_bind_blob64(stmt_, index, bytes.data(), bytes.size(),
                                              SQLITE_TRANSIENT)
                        : sqlite3_bind_zeroblob(stmt_, index, 0);
  if (rc != SQLITE_OK) {
    throw StoreError(db_->path() + ": " + db_->last_error(), db_->last_error_code());
  }
  return *this;
}

Statement& Statement::bind_null(int index) {
  if (sqlite3_bind_null(stmt_, index) != SQLITE_OK) {
    throw StoreError(db_->path() + ": " + db_->last_error(), db_->last_error_code());
  }
  return *this;
}

bool Statement::step() {
  int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  throw StoreError(db_->path() + ": " + db_->last_error(), db_->last_error_code());
}

void Statement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

bool Statement::is_null(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_NULL;
}

int64_t Statement::column_int64(int column) const { return sqlite3_column_int64(stmt_, column); }

std::string Statement::column_text(int column) const {
  const unsigned char* text = sqlite3_column_text(stmt_, column);
  return text ? std::string(reinterpret_cast<const char*>(text),
                            static_cast<size_t>(sqlite3_column_bytes(stmt_, column)))
              : std::string();
}

double Statement::column_double(int column) const { return sqlite3_column_double(stmt_, column); }

std::string Statement::column_blob(int column) const {
  // Bytes first, then size: sqlite3_column_bytes after sqlite3_column_blob
  // is the order SQLite documents as safe.
  const void* bytes = sqlite3_column_blob(stmt_, column);
  return bytes ? std::string(static_cast<const char*>(bytes),
                             static_cast<size_t>(sqlite3_column_bytes(stmt_, column)))
               : std::string();
}

}  // namespace acomms::store
