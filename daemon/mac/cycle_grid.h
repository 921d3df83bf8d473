#pragma once
// When TDMA cycles start, so that nodes that never exchange a message agree.
//
// Decentralized nodes share only UTC. Cycle k starts at
//     reference + k * cycle_length
// where the reference is a configured epoch or, without one, midnight UTC of
// the current day. Everything is integer nanoseconds (the Clock's own unit),
// so every node computes bit-identical boundaries: no floating-point drift
// after a day of cycles.
//
// Midnight. Without an epoch the grid restarts at every midnight UTC: cycle 0
// of each day starts exactly at midnight. If 86400 s is not a whole number of
// cycles, the last cycle that would run past midnight is not started: the
// remainder (86400 s mod cycle_length) before midnight is silent, and every
// node resumes with cycle 0 at midnight. Nodes agree on this without any
// message, and the cycle count resets with the day (the auto-discovery MAC
// places its blank slot from that count). A cycle longer than a day cannot
// realign daily; it gets one cycle per day, starting at midnight, cut short
// by the next midnight (make_mac refuses such fixed cycles without an epoch).
//
// With an epoch the grid never realigns: cycle k starts at epoch + k * length
// for every integer k (negative before the epoch), and the count is k.
//
// Thread-safe: a CycleGrid is an immutable value (every method is const).

#include <chrono>
#include <cstdint>
#include <optional>

#include "core/clock.h"

namespace acomms::mac {

using Nanoseconds = std::chrono::nanoseconds;

// Seconds as the grid's integer nanoseconds (rounded to the nearest; exact
// for epochs too).
Nanoseconds to_nanoseconds(double seconds);

class CycleGrid {
 public:
  using time_point = core::Clock::time_point;

  struct CycleStart {
    time_point start;
    // k: cycles since the reference (since midnight UTC without an epoch).
    int64_t count = 0;
  };

  // `cycle_length` must be positive. `epoch`: seconds since the Unix epoch.
  CycleGrid(std::optional<double> epoch, Nanoseconds cycle_length);

  Nanoseconds cycle_length() const { return length_; }

  // The first cycle that starts at or after `t`.
  CycleStart next(time_point t) const;
  // The cycle running at `t` (start <= t < start + length), or nothing in the
  // silent remainder before midnight.
  std::optional<CycleStart> containing(time_point t) const;

 private:
  std::optional<Nanoseconds> epoch_;
  Nanoseconds length_;
};

}  // namespace acomms::mac
