#pragma once
// Start-up sentences (spec §4): configuration ($CCCFG/$CACFG, $CCCFQ), the
// clock ($CCCLK/$CACLK) and the software revision ($CAREV), which tells MM1
// from MM2 and, with identifier INIT, reports a reboot.
//
// Each sentence is a plain struct with to_sentence() and a parse_*()
// that accepts only its own address(es) and checks every field it reads.

#include <string>
#include <vector>

#include "micromodem/nmea/result.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {

// Who writes a sentence that exists in both directions: "CC" or "CA".
enum class Talker { kHost, kModem };

// $CCCFG,<name>,<value> (write an NVRAM parameter) and its echo $CACFG.
// Also the answer to $CCCFQ. The echo must match both name and value
// (§4.2), so values are kept as text, exactly as written.
struct ConfigParameter {
  std::string name;   // "SRC", or an MM2 dotted name "psk.packet.mod_hdr_version"
  std::string value;  // may be empty: an MM2 group header in a dump
  bool operator==(const ConfigParameter&) const = default;
};
Sentence to_sentence(const ConfigParameter& parameter, Talker talker);
Result<ConfigParameter> parse_config_parameter(const Sentence& sentence);

// $CCCFQ,<name>: query one parameter, or ALL (MM1) / TOP (MM2) for a dump.
struct ConfigQuery {
  std::string name;
  bool operator==(const ConfigQuery&) const = default;
};
Sentence to_sentence(const ConfigQuery& query);
Result<ConfigQuery> parse_config_query(const Sentence& sentence);

// $CCCLK,yyyy,MM,dd,HH,mm,ss (set, UTC) and $CACLK (the modem's time).
struct ClockTime {
  int year = 1970, month = 1, day = 1, hour = 0, minute = 0, second = 0;
  bool operator==(const ClockTime&) const = default;
};
Sentence to_sentence(const ClockTime& time, Talker talker);
Result<ClockTime> parse_clock_time(const Sentence& sentence);

// $CAREV,<hhmmss>,<identifier>,<revision>. Identifier INIT at every boot,
// then AUV (main firmware) and, on MM2, COPROC.
struct Revision {
  std::string time;        // modem time of day, hhmmss
  std::string identifier;  // "INIT", "AUV", "COPROC"
  std::string revision;    // "0.93.0.09", "2.0.27087"
  bool operator==(const Revision&) const = default;
  bool is_boot() const { return identifier == "INIT"; }
};
Sentence to_sentence(const Revision& revision);
Result<Revision> parse_revision(const Sentence& sentence);

enum class ModemGeneration { kMM1, kMM2 };
// From an AUV revision string: major 0 → MM1, major 2 and up → MM2 (§4.1).
// Major 1 is not known to exist and is refused.
Result<ModemGeneration> modem_generation(std::string_view revision);
// "2.0.27087" → {2, 0, 27087}; "0.93.0.09" → {0, 93, 0, 9}.
Result<std::vector<int>> revision_numbers(std::string_view revision);

}  // namespace acomms::micromodem
