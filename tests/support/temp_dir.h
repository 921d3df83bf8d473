#pragma once
// A fresh directory for one test, removed when the test is done.
//
// Tests that touch files (a store, a config, a socket) each built their own
// path from temp_directory_path and the pid, and removed it in TearDown, or
// at the end of the test body, which a failed ASSERT never reaches: stores
// were left behind. Here the name carries the pid and a counter (ctest runs
// each test in its own process, and a process may hold several), the
// directory is emptied on creation (a leftover from a killed run cannot leak
// in) and removed on destruction.
//
// Names stay short on purpose: a daemon's unix socket inside must fit the
// 107 bytes of sun_path, so tests that place sockets pass "/tmp" as the base
// rather than a possibly long $TMPDIR.
//
// Thread-compatible: one owner; path() may be read from any thread.

#include <filesystem>
#include <string>
#include <string_view>

namespace acomms::testing {

class TempDir {
 public:
  // <base>/<prefix>-<pid>-<n>, created empty.
  explicit TempDir(std::string_view prefix = "acomms-test",
                   const std::filesystem::path& base = std::filesystem::temp_directory_path());
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::filesystem::path& name) const { return path_ / name; }
  std::string string() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace acomms::testing
