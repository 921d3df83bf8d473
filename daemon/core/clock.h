#pragma once
// Time for everything in acommsd. MAC slots, ttl expiry and priorities all read
// a Clock, never the system directly, so a whole multi-node network can run in
// one test process on simulated time, faster than real time and repeatably.
//
// Thread-safe: every Clock may be read from any thread (SimulatedClock under a
// mutex, so a test thread may move it while the core thread reads it).

#include <chrono>
#include <mutex>

namespace acomms::core {

class Clock {
 public:
  using time_point = std::chrono::system_clock::time_point;
  virtual ~Clock() = default;
  // Current UTC time.
  virtual time_point now() const = 0;
  // Seconds since the Unix epoch, as a double (the unit DCCL time fields use).
  double now_seconds() const;
};

// The machine's UTC clock.
class SystemClock final : public Clock {
 public:
  time_point now() const override { return std::chrono::system_clock::now(); }
};

// A clock that moves only when told to. Thread-safe, so a test thread may
// advance it while the core thread reads it.
class SimulatedClock final : public Clock {
 public:
  explicit SimulatedClock(time_point start) : now_(start) {}
  time_point now() const override;
  void set(time_point t);
  void advance(std::chrono::system_clock::duration d);

 private:
  mutable std::mutex mutex_;
  time_point now_;
};

}  // namespace acomms::core
