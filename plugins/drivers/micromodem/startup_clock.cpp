// The MM2 half of StartupSequence::set_clock (spec §4.5): `$CCTMS` with the
// next UTC second, mode 0 (no external pulse), confirmed by `$CATMS`.
//
// The reply is checked, not only awaited: `$CATMS` carries a time-out flag
// (mode 1 waits for a pulse that may never come) and the time the modem now
// keeps. goby3 sets the clock again when the skew exceeds 1 s; the modem
// answers within ~0.1 s of a command sent 50 ms after a second boundary, so
// a clock set as sent reports the carried second or the one before it
// (tolerance 2 s). Anything else is a start-up error naming what the modem
// said: its timestamps (§10 quirk 14) would be wrong.

#include <chrono>
#include <cstdlib>
#include <ctime>

#include "micromodem/nmea/time_sentences.h"
#include "micromodem/startup_sequence.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;
using nmea::Sentence;

namespace {

constexpr std::time_t kTolerance = 2;  // seconds

std::time_t seconds_of(const nmea::ClockTime& t) {
  std::tm tm{};
  tm.tm_year = t.year - 1900, tm.tm_mon = t.month - 1, tm.tm_mday = t.day;
  tm.tm_hour = t.hour, tm.tm_min = t.minute, tm.tm_sec = t.second;
  return timegm(&tm);
}

}  // namespace

void StartupSequence::set_clock_mm2(const nmea::ClockTime& carried) {
  std::weak_ptr<bool> alive = alive_;
  commands_.push({to_sentence(nmea::TimeSet{carried, 0}), [](const Sentence& s) { return s.is("CATMS"); },
                  [this, alive, carried](bool ok, const Sentence* reply, const std::string& why) {
                    if (alive.expired()) return;
                    if (!ok) return fail("the clock was not set ($CCTMS): " + why);
                    auto confirmed = nmea::parse_time_set_reply(*reply);
                    if (!confirmed) return fail("the clock was not set: " + confirmed.error().text);
                    if (confirmed->timed_out) return fail("the clock was not set: $CATMS reports a time-out");
                    std::time_t skew = std::llabs(seconds_of(confirmed->time) - seconds_of(carried));
                    if (skew > kTolerance) {
                      return fail("the clock was not set: sent " + nmea::iso_time_text(carried) +
                                  ", the modem keeps " + nmea::iso_time_text(confirmed->time));
                    }
                    finished_ = true;
                    done_("");
                  }});
}

}  // namespace acomms::drivers::micromodem
