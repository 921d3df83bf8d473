#pragma once
// The MM2 clock (spec §4.5): `$CCTMS,<yyyy-mm-ddTHH:MM:SSZ>,<mode>` sets the
// modem's clock and `$CATMS,<timed_out 0/1>,<time set>` confirms it. MM1
// firmware does not know them; it is set with $CCCLK (config_sentences.h).
//
// The time is ISO 8601 UTC in whole seconds, the only form the public
// transcripts show; a fraction or another zone is refused rather than
// guessed at.

#include <string>
#include <string_view>

#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/result.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {

// "2019-12-02T03:02:59Z" ↔ ClockTime (fields checked as for $CCCLK).
std::string iso_time_text(const ClockTime& time);
Result<ClockTime> parse_iso_time(std::string_view text);

// $CCTMS: mode 0 = apply at once (no external pulse), 1 = on the next edge
// of the external PPS line.
struct TimeSet {
  ClockTime time;
  int mode = 0;
  bool operator==(const TimeSet&) const = default;
};
Sentence to_sentence(const TimeSet& set);
Result<TimeSet> parse_time_set(const Sentence& sentence);

// $CATMS: whether the modem gave up waiting (mode 1 without a pulse), and
// the time it now keeps.
struct TimeSetReply {
  bool timed_out = false;
  ClockTime time;
  bool operator==(const TimeSetReply&) const = default;
};
Sentence to_sentence(const TimeSetReply& reply);
Result<TimeSetReply> parse_time_set_reply(const Sentence& sentence);

}  // namespace acomms::micromodem
