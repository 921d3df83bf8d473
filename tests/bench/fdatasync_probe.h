// The cost of one 4 KiB write + fdatasync in a directory: the floor under
// every durable commit on that filesystem. journal_bench and submit_bench
// print it next to their figures, because on a given machine it, more than
// the code, sets how many durable commits per second are possible, and how
// long each Submit must wait at the least.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace acomms::bench {

// Mean seconds per write + fdatasync over `count` rounds. Two cases, as a
// WAL sees them: `extend` appends to a growing file (the WAL before its
// first checkpoint: the file size changes, so the filesystem journal commits
// too); otherwise one block is rewritten in place (a WAL reused after a
// checkpoint, the steady state). Throws std::runtime_error if the directory
// cannot be written.
inline double fdatasync_seconds(const std::string& dir, int count, bool extend) {
  const std::string path = dir + "/acomms_fsync_probe_" + std::to_string(::getpid());
  auto fail = [&path](const char* what) {
    throw std::runtime_error(path + ": " + what + ": " + std::strerror(errno));
  };
  int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot create");
  // Closes and removes the probe file however the measurement ends.
  struct Cleanup {
    int fd;
    const std::string& path;
    ~Cleanup() {
      ::close(fd);
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
    }
  } cleanup{fd, path};
  const std::string block(4096, 'x');
  // In place: the block exists and is on disk before timing starts.
  if (!extend && (::pwrite(fd, block.data(), block.size(), 0) < 0 || ::fsync(fd) != 0)) fail("write");
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < count; ++i) {
    const off_t offset = extend ? static_cast<off_t>(i) * 4096 : 0;
    if (::pwrite(fd, block.data(), block.size(), offset) < 0 || ::fdatasync(fd) != 0) fail("write");
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / count;
}

}  // namespace acomms::bench
