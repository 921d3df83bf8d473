#pragma once
// Failures of the store, with SQLite's result code when it had one.
//
// Thread-safe as any exception: set once when thrown, then only read.

#include <sqlite3.h>

#include <stdexcept>
#include <string>

namespace acomms::store {

// Any failure of the store: the message says which file and what to do.
// When SQLite reported it, code() is SQLite's (extended) result code, so
// that a caller can tell a full disk, which an operator can free, from an
// I/O error; 0 otherwise.
class StoreError : public std::runtime_error {
 public:
  explicit StoreError(const std::string& what, int code = 0) : std::runtime_error(what), code_(code) {}
  int code() const { return code_; }
  // SQLITE_FULL: the disk (or the file's size limit) has no room for the write.
  bool disk_full() const { return (code_ & 0xff) == SQLITE_FULL; }

 private:
  int code_;
};

}  // namespace acomms::store
