#pragma once
// A seafloor LBL transponder in the fake water (spec §7.2-§7.3). It is no
// modem: it only answers interrogations. A narrowband transponder answers a
// $CCPNT that listens on its reply frequency; a REMUS digital one answers a
// $CCPDT that listens for its beacon letter, on any channel (the fake's
// choice: the spec does not say how channels and beacons pair). One set to
// `answers = false` never replies, as a dead or out-of-range transponder.

#include <chrono>

#include "acoustic_packet.h"

namespace acomms::fake_micromodem {

struct Transponder {
  enum class Kind { kNarrowband, kRemus };
  Kind kind = Kind::kNarrowband;
  int reply_frequency_hz = 26000;  // narrowband
  char beacon = 'A';               // REMUS: A..D
  Position position;
  bool answers = true;
  // Its own turnaround; the interrogating modem removes NVRAM TAT, so a
  // TAT that differs shows up in the travel time as (turnaround - TAT) / 2.
  std::chrono::milliseconds turnaround{50};
};

}  // namespace acomms::fake_micromodem
