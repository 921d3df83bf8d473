#include "faulty_vfs.h"

#include <mutex>
#include <optional>
#include <stdexcept>

namespace acomms::store::testing {
namespace {

// Our file: the header SQLite sees, then the real file the default VFS
// fills in (szOsFile covers both).
struct FaultyFile {
  sqlite3_file base;
  VfsFile kind;
  sqlite3_file* real;
};

sqlite3_vfs* real_vfs = nullptr;

struct Plan {
  std::mutex mutex;
  std::optional<VfsFault> fault;
  int64_t matches = 0;
  int64_t failures = 0;
};

Plan& plan() {
  static Plan p;
  return p;
}

bool file_matches(VfsFile wanted, VfsFile actual) { return wanted == VfsFile::kAny || wanted == actual; }

sqlite3_file* real(sqlite3_file* file) { return reinterpret_cast<FaultyFile*>(file)->real; }

int fault(sqlite3_file* file, VfsCall call) {
  return FaultyVfs::instance().fault_for(call, reinterpret_cast<FaultyFile*>(file)->kind);
}

int x_close(sqlite3_file* f) { return real(f)->pMethods->xClose(real(f)); }

int x_read(sqlite3_file* f, void* buffer, int amount, sqlite3_int64 offset) {
  if (int rc = fault(f, VfsCall::kRead)) return rc;
  return real(f)->pMethods->xRead(real(f), buffer, amount, offset);
}

int x_write(sqlite3_file* f, const void* buffer, int amount, sqlite3_int64 offset) {
  if (int rc = fault(f, VfsCall::kWrite)) return rc;
  return real(f)->pMethods->xWrite(real(f), buffer, amount, offset);
}

int x_truncate(sqlite3_file* f, sqlite3_int64 size) {
  if (int rc = fault(f, VfsCall::kTruncate)) return rc;
  return real(f)->pMethods->xTruncate(real(f), size);
}

int x_sync(sqlite3_file* f, int flags) {
  if (int rc = fault(f, VfsCall::kSync)) return rc;
  return real(f)->pMethods->xSync(real(f), flags);
}

int x_file_size(sqlite3_file* f, sqlite3_int64* size) { return real(f)->pMethods->xFileSize(real(f), size); }

int x_lock(sqlite3_file* f, int level) {
  if (int rc = fault(f, VfsCall::kLock)) return rc;
  return real(f)->pMethods->xLock(real(f), level);
}

int x_unlock(sqlite3_file* f, int level) { return real(f)->pMethods->xUnlock(real(f), level); }

int x_check_reserved_lock(sqlite3_file* f, int* out) {
  return real(f)->pMethods->xCheckReservedLock(real(f), out);
}

int x_file_control(sqlite3_file* f, int op, void* arg) {
  return real(f)->pMethods->xFileControl(real(f), op, arg);
}

int x_sector_size(sqlite3_file* f) { return real(f)->pMethods->xSectorSize(real(f)); }

int x_device_characteristics(sqlite3_file* f) { return real(f)->pMethods->xDeviceCharacteristics(real(f)); }

int x_shm_map(sqlite3_file* f, int region, int size, int extend, void volatile** out) {
  if (int rc = fault(f, VfsCall::kShmMap)) return rc;
  return real(f)->pMethods->xShmMap(real(f), region, size, extend, out);
}

int x_shm_lock(sqlite3_file* f, int offset, int n, int flags) {
  // Unlocking must always work: SQLite does not expect it to fail.
  if ((flags & SQLITE_SHM_LOCK) != 0) {
    if (int rc = fault(f, VfsCall::kShmLock)) return rc;
  }
  return real(f)->pMethods->xShmLock(real(f), offset, n, flags);
}

void x_shm_barrier(sqlite3_file* f) { real(f)->pMethods->xShmBarrier(real(f)); }

int x_shm_unmap(sqlite3_file* f, int delete_flag) { return real(f)->pMethods->xShmUnmap(real(f), delete_flag); }

int x_fetch(sqlite3_file* f, sqlite3_int64 offset, int amount, void** out) {
  return real(f)->pMethods->xFetch(real(f), offset, amount, out);
}

int x_unfetch(sqlite3_file* f, sqlite3_int64 offset, void* page) {
  return real(f)->pMethods->xUnfetch(real(f), offset, page);
}

const sqlite3_io_methods kMethods = {
    3,           x_close,        x_read,          x_write,         x_truncate,
    x_sync,      x_file_size,    x_lock,          x_unlock,        x_check_reserved_lock,
    x_file_control, x_sector_size, x_device_characteristics, x_shm_map, x_shm_lock,
    x_shm_barrier, x_shm_unmap,  x_fetch,         x_unfetch,
};

int x_open(sqlite3_vfs*, sqlite3_filename name, sqlite3_file* file, int flags, int* out_flags) {
  auto* ours = reinterpret_cast<FaultyFile*>(file);
  ours->base.pMethods = nullptr;
  ours->kind = (flags & SQLITE_OPEN_MAIN_DB) != 0 ? VfsFile::kMainDb
               : (flags & SQLITE_OPEN_WAL) != 0   ? VfsFile::kWal
                                                  : VfsFile::kOther;
  ours->real = reinterpret_cast<sqlite3_file*>(ours + 1);
  if (int rc = FaultyVfs::instance().fault_for(VfsCall::kOpen, ours->kind)) return rc;
  int rc = real_vfs->xOpen(real_vfs, name, ours->real, flags, out_flags);
  // SQLite calls xClose only on a file whose pMethods is set.
  if (ours->real->pMethods != nullptr) ours->base.pMethods = &kMethods;
  return rc;
}

}  // namespace

FaultyVfs::FaultyVfs() {
  real_vfs = sqlite3_vfs_find(nullptr);
  if (real_vfs == nullptr || real_vfs->iVersion < 2) throw std::runtime_error("faulty vfs: no usable default VFS");
  // Everything but xOpen is the default VFS's own (they take our vfs
  // pointer, and read only the fields copied with them).
  static sqlite3_vfs vfs = *real_vfs;
  vfs.zName = kName;
  vfs.pNext = nullptr;
  vfs.szOsFile = static_cast<int>(sizeof(FaultyFile)) + real_vfs->szOsFile;
  vfs.xOpen = x_open;
  if (sqlite3_vfs_register(&vfs, 0) != SQLITE_OK) throw std::runtime_error("faulty vfs: cannot register");
}

FaultyVfs& FaultyVfs::instance() {
  static FaultyVfs vfs;
  return vfs;
}

void FaultyVfs::arm(const VfsFault& fault) {
  std::lock_guard lock(plan().mutex);
  plan().fault = fault;
  plan().matches = 0;
  plan().failures = 0;
}

void FaultyVfs::disarm() {
  std::lock_guard lock(plan().mutex);
  plan().fault.reset();
}

int64_t FaultyVfs::failures() const {
  std::lock_guard lock(plan().mutex);
  return plan().failures;
}

int64_t FaultyVfs::matches() const {
  std::lock_guard lock(plan().mutex);
  return plan().matches;
}

int FaultyVfs::fault_for(VfsCall call, VfsFile file) {
  std::lock_guard lock(plan().mutex);
  const std::optional<VfsFault>& f = plan().fault;
  if (!f || f->call != call || !file_matches(f->file, file)) return SQLITE_OK;
  const int64_t n = plan().matches++;
  if (n < f->skip || (!f->persistent && n > f->skip)) return SQLITE_OK;
  ++plan().failures;
  return f->code;
}

}  // namespace acomms::store::testing
