#include "link/driver.h"

#include "link/rate_table.h"

namespace acomms::link {

namespace {

std::chrono::nanoseconds with_margin(std::chrono::nanoseconds time) {
  return std::chrono::nanoseconds(static_cast<int64_t>(static_cast<double>(time.count()) * (1 + kAirTimeMargin)));
}

}  // namespace

DriverCounters& DriverCounters::operator+=(const DriverCounters& other) {
  lost_half_duplex += other.lost_half_duplex;
  lost_collision += other.lost_collision;
  for (const auto& [kind, count] : other.bad_input) bad_input[kind] += count;
  return *this;
}

std::chrono::nanoseconds Driver::packet_air_time(int32_t rate, uint32_t num_frames) const {
  const ModemRate* row = find_rate(rate);
  if (row == nullptr) return std::chrono::nanoseconds(0);
  return with_margin(link::packet_air_time(*row, num_frames));
}

std::chrono::nanoseconds Driver::ack_time(int32_t) const { return with_margin(kTurnaround + kMiniPacket); }

double Driver::sound_speed() const { return kNominalSoundSpeed; }

DriverSpecificResult Driver::check_driver_specific(const v1::ModemTransmission& request) const {
  return driver_specific_error(DriverSpecificStatus::kUnimplemented,
                               "does not support the driver-specific request " + describe_driver_specific(request),
                               request);
}

void Driver::send_driver_specific(const v1::ModemTransmission& request, double, DriverSpecificDone done) {
  done(check_driver_specific(request));
}

}  // namespace acomms::link
