#pragma once
// How long the fake modem takes for things (spec §3.1, §9). Air times are
// the spec's estimates (0.3 s of probe and guard plus the bits); partial
// packets: each carried frame costs a full frame's time (§3 "a frame
// shorter than the maximum takes the same air time as a full frame").
// The rest are the fake's choices inside the spec's ranges (README.md).

#include <chrono>

namespace acomms::fake_micromodem {

using std::chrono::milliseconds;
using Duration = std::chrono::system_clock::duration;

struct ModemTiming {
  Duration echo = milliseconds(50);          // command → echo: "< 0.1 s"
  Duration nvram_write = milliseconds(100);  // $CCCFG → $CACFG: "~0.1 s"
  Duration time_query = milliseconds(500);   // $CCTMQ → $CATMQ: "~0.5 s"
  Duration dump_line = milliseconds(20);     // between the lines of a $CCCFQ,ALL dump
  Duration mini_air = milliseconds(700);     // any mini-packet: "0.5-0.7 s"
  Duration decode = milliseconds(100);       // end of sound → $CARXD/$CACST
  Duration turnaround = milliseconds(500);   // packet decoded → ACK starts: "~0.5 s"
  Duration boot = milliseconds(1000);        // $CAREV,INIT → $CAREV,AUV
  Duration revision_period = std::chrono::seconds(60);  // REV=1 (period not public)
};

// Rate table (§3.1): frames per packet and bytes per frame.
struct RateShape {
  int frames;
  int frame_bytes;
  double full_packet_seconds;
};
inline constexpr RateShape kRates[7] = {
    {1, 32, 3.5}, {3, 64, 6.4}, {3, 64, 3.4}, {2, 256, 3.7},
    {2, 256, 3.5}, {8, 256, 3.4}, {6, 32, 3.25},
};

// Air time of a data packet carrying `frames` frames at `rate` (0..6).
inline Duration data_air_time(int rate, int frames) {
  const RateShape& shape = kRates[rate];
  double per_frame = (shape.full_packet_seconds - 0.3) / shape.frames;
  double seconds = 0.3 + per_frame * (frames < 1 ? 1 : frames);
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(seconds));
}

}  // namespace acomms::fake_micromodem
