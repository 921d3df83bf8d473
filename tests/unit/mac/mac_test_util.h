#pragma once
// Shared by the MAC tests: a simulated day and a fake driver that records
// what a MAC asks it to send, and when.

#include <chrono>
#include <cstdint>
#include <vector>

#include "acomms/v1/modem_transmission.pb.h"
#include "core/scheduler.h"
#include "mac/mac.h"

namespace acomms::mac::testing {

// 2024-06-01T00:00:00Z, a midnight.
constexpr int64_t kDay = 1717200000;

// Midnight + `ns` nanoseconds, exactly.
inline core::Clock::time_point day_ns(int64_t ns) {
  return core::Clock::time_point(std::chrono::seconds(kDay) + std::chrono::nanoseconds(ns));
}
inline core::Clock::time_point day_s(int64_t s) { return day_ns(s * 1'000'000'000); }
inline core::Clock::time_point day_ms(int64_t ms) { return day_ns(ms * 1'000'000); }

struct Sent {
  core::Clock::time_point when;  // the scheduler's clock at the call
  v1::ModemTransmission transmission;
};

// The driver end of Mac::start: records every transmission.
class FakeDriver {
 public:
  explicit FakeDriver(const core::Scheduler& scheduler) : scheduler_(scheduler) {}
  Mac::Transmit transmit() {
    return [this](const v1::ModemTransmission& t) {
      sent.push_back({scheduler_.clock().now(), t});
    };
  }
  std::vector<core::Clock::time_point> times() const {
    std::vector<core::Clock::time_point> out;
    for (const Sent& s : sent) out.push_back(s.when);
    return out;
  }
  std::vector<Sent> sent;

 private:
  const core::Scheduler& scheduler_;
};

inline Slot slot(int32_t src, double seconds, int32_t dest = -1, int32_t rate = 0) {
  Slot s;
  s.src = src;
  s.seconds = seconds;
  s.dest = dest;
  s.rate = rate;
  return s;
}

}  // namespace acomms::mac::testing
