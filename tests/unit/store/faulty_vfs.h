#pragma once
// A SQLite VFS for tests that fails the calls a test chooses.
//
// The problem: the store's failure paths (a BEGIN, a savepoint or a COMMIT
// that fails mid-batch, a full disk) only run when the disk misbehaves, which
// a test cannot arrange with real files. SQLite's own answer is to test
// through a VFS that injects the faults; this is ours.
//
// The decision: "acomms-faulty" wraps the default (unix) VFS and passes every
// call through, except that once a Fault is armed, the matching calls return
// its error code instead of touching the file. Open a store on it by name
// (store::Store::Options::vfs); every other connection to the same file, on
// the default VFS, sees the file as the faulty one left it.
//
// Thread-safety: arm/disarm/counters from the test's thread while the store
// writer's thread runs SQLite through the VFS: the plan is under a mutex.

#include <sqlite3.h>

#include <cstdint>
#include <string>

namespace acomms::store::testing {

// The VFS calls a fault can hit.
enum class VfsCall { kOpen, kRead, kWrite, kSync, kTruncate, kLock, kShmMap, kShmLock };
// Which file a call is on: a fault names one, or kAny. kShmLock and kShmMap
// are calls on the main database file (the wal-index is reached through
// it); kOther is every other file (a rollback journal, a temporary file).
enum class VfsFile { kAny, kMainDb, kWal, kOther };

struct VfsFault {
  VfsCall call = VfsCall::kWrite;
  VfsFile file = VfsFile::kAny;
  // The error returned: SQLITE_IOERR_WRITE, SQLITE_IOERR_FSYNC, SQLITE_FULL...
  int code = SQLITE_IOERR;
  // Matching calls let through before the first failure.
  int skip = 0;
  // Fail every matching call from then on (a dead disk, a full one), or
  // only one (a transient error).
  bool persistent = true;
};

class FaultyVfs {
 public:
  static constexpr const char* kName = "acomms-faulty";

  // Registers the VFS (once per process, not as the default) and returns it.
  static FaultyVfs& instance();

  // Replaces any armed fault; counters restart.
  void arm(const VfsFault& fault);
  // Every call passes through again.
  void disarm();
  // Calls failed since arm().
  int64_t failures() const;
  // Matching calls seen since arm(), failed or not.
  int64_t matches() const;

  // For the VFS's own functions: the code to return for this call, or
  // SQLITE_OK to pass it through.
  int fault_for(VfsCall call, VfsFile file);

 private:
  FaultyVfs();
};

// Arms a fault for the life of a scope and disarms it at the end, so that a
// failed assertion never leaves the next test on a broken disk.
class ScopedVfsFault {
 public:
  explicit ScopedVfsFault(const VfsFault& fault) { FaultyVfs::instance().arm(fault); }
  ~ScopedVfsFault() { FaultyVfs::instance().disarm(); }
  ScopedVfsFault(const ScopedVfsFault&) = delete;
  ScopedVfsFault& operator=(const ScopedVfsFault&) = delete;
};

}  // namespace acomms::store::testing
