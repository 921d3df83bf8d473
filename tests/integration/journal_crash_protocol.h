#pragma once
// What journal_crash_child prints and stores, shared with the test that
// kills it (journal_crash_test.cpp).
//
// Each appender thread k appends payload(k, 0), payload(k, 1), ... one at a
// time, so what a thread attempted is known from what it printed: everything
// up to the last printed seq, plus at most one more in flight.
//
// stdout lines, each written by one write(2) once the fact is durable:
//   ok <id> <thread> <seq>   append() returned id for payload(thread, seq)
//   removed <id>             an "acked" removal of <id> was recorded and flushed
// Messages with seq % kRemoveEvery == 0 are removed right after their ok line.

#include <cstdint>
#include <string>

namespace acomms::testing::journal_crash {

inline constexpr int kRemoveEvery = 5;

// Binary on purpose (a NUL and a 0xff): payloads are BLOBs, not text.
inline std::string payload(int thread, int64_t seq) {
  std::string tag = "t" + std::to_string(thread) + "-" + std::to_string(seq);
  return tag + std::string("\0\xff", 2) + std::string(48, 'p');
}

}  // namespace acomms::testing::journal_crash
