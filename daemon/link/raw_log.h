#pragma once
// Every byte to and from the modem, for the person debugging a link.
//
// The problem: a modem misbehaves at sea, days later someone asks what it
// said; the daemon's log holds only summaries, and an unbounded capture
// would fill the vehicle's disk. The decision: one line per chunk the
// driver reports (a Micro-Modem sentence, a datagram), stamped with UTC to
// the microsecond and its direction ("<<" from the modem, ">>" to it), in
// a text file that rotates at `max_bytes`: the full file becomes
// `<name>.1` (replacing the older one) and a new one starts. So at most
// twice max_bytes are ever on disk. Bytes outside printable ASCII are
// written as \xHH so the file stays one record per line.
//
// Not thread-safe: the core thread owns it (the driver's on_raw).

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "core/clock.h"

namespace acomms::link {

class RawLog {
 public:
  // Opens (appends to) `path`. Throws std::runtime_error naming the file
  // when it cannot be opened.
  RawLog(std::filesystem::path path, uint64_t max_bytes, const core::Clock& clock);

  void record(std::string_view bytes, bool outgoing);

  const std::filesystem::path& path() const { return path_; }
  uint64_t rotations() const { return rotations_; }

  // "2026-11-23T18:03:29.123456Z << $CAREV,...": the line record() writes
  // (without its newline).
  static std::string format(core::Clock::time_point at, std::string_view bytes, bool outgoing);

 private:
  void open();
  void rotate();

  std::filesystem::path path_;
  uint64_t max_bytes_;
  const core::Clock& clock_;
  std::ofstream file_;
  uint64_t size_ = 0;
  uint64_t rotations_ = 0;
};

}  // namespace acomms::link
