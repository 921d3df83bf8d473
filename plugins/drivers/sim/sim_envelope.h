#pragma once
// What one simulated modem tells the others about a transmission: who sent
// it, from where, when its first sound left, how long it lasts, and the
// transmission itself. Each receiver works out from this, with its own
// position and its own history, whether and when it hears it.
//
// In one process the envelope is passed as is (SimChannel); between
// processes it travels as one UDP datagram (LoopbackMedium), encoded here:
//   "ASIM" version:u8 sender:i32 x:f64 y:f64 z:f64 start_ns:i64
//   duration_ns:i64 transmission_length:u32 transmission (protobuf)
// all little-endian. Times are nanoseconds since the Unix epoch on the
// senders' shared clock (loopback means one machine, one clock).

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "acomms/v1/modem_transmission.pb.h"
#include "core/clock.h"

namespace acomms::drivers {

struct SimPosition {
  double x = 0, y = 0, z = 0;  // metres (the frame of sim.proto's Position)
};

double distance(const SimPosition& a, const SimPosition& b);

struct SimEnvelope {
  int32_t sender = 0;
  SimPosition position;
  core::Clock::time_point start;
  std::chrono::nanoseconds duration{0};
  v1::ModemTransmission transmission;
};

std::string encode(const SimEnvelope& envelope);
// nullopt, with `error` saying what is wrong, for anything that is not a
// well-formed envelope: the loopback socket may receive anything. Beyond
// its layout, an envelope must be physically possible: a sender id >= 0,
// coordinates within 10,000 km, a duration of at most 10 minutes and a
// start between 1970 and 2100, so that hearing() stays within range.
std::optional<SimEnvelope> decode_envelope(std::string_view bytes, std::string* error);

// When a modem at `at` hears the envelope's sound: from `start` to `end` on
// the shared clock, after travelling `range_m` at `sound_speed_mps`.
struct SimHearing {
  double range_m = 0;
  core::Clock::time_point start;
  core::Clock::time_point end;
};
// nullopt when the sound would take longer than a day to arrive (so far, or
// so slow, that no simulation waits for it).
std::optional<SimHearing> hearing(const SimEnvelope& envelope, const SimPosition& at, double sound_speed_mps);

}  // namespace acomms::drivers
