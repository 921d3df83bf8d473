#pragma once
// The WHOI Micro-Modem rate table: how many frames of how many bytes a
// packet at each rate carries, and how long it is in the water.
//
// Every driver offers the queues these limits unless its config says
// otherwise, so that a message plan tested on the simulator or on UDP fits
// the real modem. The simulator also needs the air time.
//
// Frames and frame sizes are the Micro-Modem's (rates 0..5: 1x32, 3x64,
// 3x64, 2x256, 2x256, 8x256 bytes). Air times are derived, not measured:
// public WHOI figures give the burst bit rates (80 bps FH-FSK for rate 0;
// PSK 250, 500, 1200, 1300, 5300 bps for rates 1..5; the WHOI data-rate
// page, acomms.whoi.edu/micro-modem, quotes "80-5400 bps" and a ~5 kbps
// rate-5 burst), and its PSK table shows a packet's signal carrying about
// 0.3 s of probe + guard before the data (3.25 s signal for a 2.95 s packet
// at rate 6). So:
//   air time = 0.3 s + frames x frame bytes x 8 / bit rate
// e.g. rate 0, one frame: 0.3 + 256 / 80 = 3.5 s; rate 5, eight frames:
// 0.3 + 16384 / 5300 = 3.391 s. Short "mini-packets" (a poll, a software
// ACK) are modelled as 32 bits at 80 bps after the same 0.3 s: 0.7 s.
//
// Thread-safe: constant data and pure functions.

#include <chrono>
#include <cstdint>

namespace acomms::link {

struct ModemRate {
  int32_t rate;
  uint32_t max_num_frames;
  uint32_t max_frame_bytes;
  uint32_t bits_per_second;  // burst rate of the data part
};

inline constexpr int32_t kMinRate = 0;
inline constexpr int32_t kMaxRate = 5;
inline constexpr std::chrono::milliseconds kPacketHeader{300};  // probe + guard
inline constexpr std::chrono::milliseconds kMiniPacket{700};    // poll, ACK
// From the end of a packet heard to the start of the answer (ACK, poll
// response): the Micro-Modem's receive-to-transmit turnaround, roughly.
inline constexpr std::chrono::milliseconds kTurnaround{500};
// Sea water, m/s: how far a packet's sound has come, for slot guards.
inline constexpr double kNominalSoundSpeed = 1500;

// The row for `rate`, or nullptr when rate is outside 0..5.
const ModemRate* find_rate(int32_t rate);

// Air time of a DATA packet carrying `num_frames` whole frames at `rate`
// (which must be valid). Frames are sent whole, padded to the frame size.
std::chrono::nanoseconds packet_air_time(const ModemRate& rate, uint32_t num_frames);

}  // namespace acomms::link
