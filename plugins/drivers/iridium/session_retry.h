#pragma once
// How long to wait after a failed session before the next one (spec §6.3).
//
// The problem: a modem that cannot reach a satellite fails fast, and a
// driver that simply tries again turns that into a tight loop of sessions
// (each one energy, and on some plans money). The decision: Ground
// Control's adaptive scheme, with the project's floor of 10 s between
// session starts after a failure: the first two retries at a random 0-5 s,
// the next two at 0-30 s (each at least the floor), then every 5 minutes
// until a session succeeds. A status with its own wait (mo_status.h) takes
// the longer of the two.
//
// Thread-safety: none; the driver's (core thread).

#include <chrono>
#include <cstdint>
#include <random>

namespace acomms::drivers::iridium {

class SessionRetry {
 public:
  static constexpr std::chrono::seconds kFloor{10};
  static constexpr std::chrono::seconds kSteady{300};

  explicit SessionRetry(uint64_t seed) : random_(seed) {}

  // The wait after one more consecutive failure.
  std::chrono::milliseconds next();
  // A session succeeded: the next failure starts the schedule again.
  void reset() { failures_ = 0; }
  uint32_t failures() const { return failures_; }

 private:
  std::mt19937_64 random_;
  uint32_t failures_ = 0;
};

}  // namespace acomms::drivers::iridium
