// A driver stand-in with the simulator's exact timing: the rate table's air
// time, and 0.5 s turnaround + 0.7 s for an ACK, with no margin. Shared by
// the slot budget's and the --check-config slot check's tests.
#pragma once

#include <chrono>
#include <cstdint>

#include "link/driver.h"
#include "link/rate_table.h"

namespace acomms::link::testing {

class ExactModem final : public Driver {
 public:
  void start(DriverCallbacks) override {}
  void stop() override {}
  void do_work() override {}
  void initiate_transmission(const v1::ModemTransmission&) override {}
  std::chrono::nanoseconds packet_air_time(int32_t rate, uint32_t num_frames) const override {
    return link::packet_air_time(*find_rate(rate), num_frames);
  }
  std::chrono::nanoseconds ack_time(int32_t) const override { return kTurnaround + kMiniPacket; }
};

}  // namespace acomms::link::testing
