#pragma once
// The fake modem's private records of what is in progress (see
// fake_micromodem.h): one exchange it transmits in, one packet it receives.

#include <cstdint>
#include <vector>

#include "acoustic_packet.h"
#include "fake_micromodem.h"
#include "micromodem/nmea/cycle_sentences.h"

namespace acomms::fake_micromodem {

struct FakeMicroModem::Exchange {
  uint64_t id = 0;
  micromodem::Cycle cycle;
  bool polled = false;         // another modem's cycle-init asked for it
  int frames_wanted = 1;       // Nframes capped by the rate
  bool awaiting_frame = false; // a $CADRQ is outstanding
  std::vector<DataFrame> frames;
};

struct FakeMicroModem::Reception {
  uint64_t id = 0;
  AcousticPacket packet;
  double range_m = 0;
  bool damaged = false;  // another arrival overlapped it
};

}  // namespace acomms::fake_micromodem
