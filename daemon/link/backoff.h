#pragma once
// Exponential backoff: how long to wait before the next attempt to reopen a
// device, reconnect to a peer or restart a driver.
//
// A device that has gone away usually stays away for a while (a cable
// unplugged, a modem rebooting); retrying at a fixed short interval floods
// the log and the bus, retrying rarely loses time when it comes back. So the
// delay starts at `min`, doubles with every consecutive failure and stops
// growing at `max`; a success resets it.

#include <chrono>
#include <string>

namespace acomms::link {

class Backoff {
 public:
  using duration = std::chrono::nanoseconds;
  // Seconds; min <= 0 means 1 s, max < min means max = min.
  Backoff(double min_s, double max_s);

  // The delay to wait now; the following one is twice as long (up to max).
  duration next();
  // The delay next() would return.
  duration peek() const { return current_; }
  // After a success: the next failure waits only `min` again.
  void reset() { current_ = min_; }

  duration min() const { return min_; }
  duration max() const { return max_; }

 private:
  duration min_;
  duration max_;
  duration current_;
};

// Seconds as a duration, rounded to the nanosecond.
Backoff::duration seconds_to_duration(double seconds);
double duration_to_seconds(Backoff::duration d);
// "0.25 s", "60 s": for log lines and status.
std::string format_seconds(Backoff::duration d);

}  // namespace acomms::link
