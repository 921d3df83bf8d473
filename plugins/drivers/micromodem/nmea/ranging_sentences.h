#pragma once
// Ranging and navigation sentences (spec §7.1-§7.3, §8.4-§8.5): the
// two-way ping between modems ($CCMPC → $CAMPC echo, $CAMPA at the target,
// $CAMPR back at the pinger) and LBL interrogations of seafloor
// transponders, narrowband ($CCPNT) and REMUS digital ($CCPDT), answered by
// $SNTTA with one-way travel times.

#include <array>
#include <optional>
#include <string>

#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/result.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {

// $CCMPC / $CAMPC / $CAMPA,<SRC>,<DEST>: the ping command, its echo, and
// (at the target) "a ping for us was received".
struct Ping {
  int source = 0;
  int destination = 0;
  bool operator==(const Ping&) const = default;
};
// `type` is "MPC" or "MPA"; the talker follows `talker`.
Sentence to_sentence(const Ping& ping, Talker talker, const char* type = "MPC");
Result<Ping> parse_ping(const Sentence& sentence);  // CCMPC, CAMPC, CAMPA

// $CAMPR,<SRC>,<DEST>,<travel time>: SRC = the modem that replied, DEST =
// us (flipped relative to $CCMPC); one-way travel time in seconds.
struct PingReply {
  int source = 0;
  int destination = 0;
  double travel_time_s = 0;
  bool operator==(const PingReply&) const = default;
};
Sentence to_sentence(const PingReply& reply);
Result<PingReply> parse_ping_reply(const Sentence& sentence);

inline constexpr int kTransponders = 4;  // A..D

// $CCPNT,<Ftx>,<Ttx>,<Trx>,<Timeout>,<FA>,<FB>,<FC>,<FD>,<Tflag>.
struct NarrowbandInterrogation {
  int transmit_frequency_hz = 25000;
  int transmit_ms = 5;
  int receive_ms = 5;
  int timeout_ms = 4000;
  std::array<int, kTransponders> reply_frequency_hz{};  // 0 = unused
  bool transmit = true;
  bool operator==(const NarrowbandInterrogation&) const = default;
};
Sentence to_sentence(const NarrowbandInterrogation& interrogation);
Result<NarrowbandInterrogation> parse_narrowband_interrogation(const Sentence& sentence);

// $CCPDT,<GRP>,<CHANNEL>,<SF>,<STO>,<Timeout>,<AF>,<BF>,<CF>,<DF>.
struct RemusInterrogation {
  int group = 1;
  int channel = 1;
  bool sync_pps = false;
  int pps_timeout = 0;
  int timeout_ms = 4000;
  std::array<bool, kTransponders> listen{};
  bool operator==(const RemusInterrogation&) const = default;
};
Sentence to_sentence(const RemusInterrogation& interrogation);
Result<RemusInterrogation> parse_remus_interrogation(const Sentence& sentence);

// $SNTTA,<TA>,<TB>,<TC>,<TD>,<hhmmss.ss>: one-way travel times; an empty
// field = no reply.
struct TravelTimes {
  std::array<std::optional<double>, kTransponders> travel_time_s{};
  std::string time;
  bool operator==(const TravelTimes&) const = default;
};
Sentence to_sentence(const TravelTimes& times);
Result<TravelTimes> parse_travel_times(const Sentence& sentence);

}  // namespace acomms::micromodem
