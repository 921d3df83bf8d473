#pragma once
// A time point as seconds (a double) since its clock's epoch.
//
// Slot arithmetic, log fields, the proto `time` fields and the command-line
// client all want "seconds since the epoch" as a double; the same
// duration<double>(t.time_since_epoch()).count() was spelled out in some
// sixteen places. With the project's clocks (core::Clock, the system clock)
// the epoch is the Unix epoch, so this is Unix time.
//
// Thread-safe: pure functions (unix_seconds_now reads the system clock).

#include <chrono>

namespace acomms::util {

template <class Clock, class Duration>
double seconds_since_epoch(std::chrono::time_point<Clock, Duration> t) {
  return std::chrono::duration<double>(t.time_since_epoch()).count();
}

// Now on the system clock, as Unix seconds: for wall-clock stamps only;
// daemon logic takes its time from core::Clock.
inline double unix_seconds_now() { return seconds_since_epoch(std::chrono::system_clock::now()); }

}  // namespace acomms::util
