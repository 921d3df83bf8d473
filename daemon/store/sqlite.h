#pragma once
// Thin RAII wrappers over the SQLite C API: a connection and a prepared
// statement. Every failure throws StoreError carrying SQLite's own message.
//
// Not thread-safe: connections are opened SQLITE_OPEN_NOMUTEX, so a Database
// and its Statements belong to one thread at a time (the store writer's, or a
// reader's own connection under its lock).

#include <sqlite3.h>

#include <cstdint>
#include <string>
#include <string_view>

#include "store/store_error.h"

namespace acomms::store {

class Statement;

class Database {
 public:
  enum class Mode { kReadWrite, kReadOnly };
  // Opens the database file: read-write (creating it if missing), or
  // read-only (it must exist). Throws StoreError.
  explicit Database(const std::string& path, Mode mode = Mode::kReadWrite)
      : Database(path, mode, std::string()) {}
  // The same through the registered sqlite3_vfs named `vfs` (the default VFS
  // when empty). For tests only: the fault-injecting VFS of tests/unit/store.
  Database(const std::string& path, Mode mode, const std::string& vfs);
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  // Runs one or more statements that return no rows.
  void exec(std::string_view sql);
  Statement prepare(std::string_view sql);
  const std::string& path() const { return path_; }
  sqlite3* handle() { return db_; }

  // SQLite's message for the last failure on this connection.
  std::string last_error() const;
  // SQLite's extended result code for it (StoreError::code()).
  int last_error_code() const;

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

class Statement {
 public:
  Statement(Database& db, std::string_view sql);
  ~Statement();
  Statement(Statement&& other) noexcept;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement& operator=(Statement&&) = delete;

  // Parameters are 1-based, as in SQL.
  Statement& bind(int index, int64_t value);
  Statement& bind(int index, std::string_view text);
  // Distinct names: an int argument would be ambiguous between the
  // integer and real overloads.
  Statement& bind_double(int index, double value);
  Statement& bind_blob(int index, std::string_view bytes);
  Statement& bind_null(int index);
  // Advances to the next row: true while there is one.
  bool step();
  void reset();

  bool is_null(int column) const;
  int64_t column_int64(int column) const;
  std::string column_text(int column) const;
  double column_double(int column) const;
  std::string column_blob(int column) const;

 private:
  Database* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace acomms::store
