#pragma once
// One NMEA-0183 sentence as the Micro-Modem speaks it (spec §2):
//   $<TT><SSS>,<field1>,...,<fieldN>*<HH><CR><LF>
// HH is the XOR of every byte strictly between '$' and '*', upper-case hex.
//
// parse_sentence() takes one line (as the LineFramer yields it, or with its
// CR/LF still on) and either returns the talker, type and fields, or says
// exactly what is wrong with it. The modem always sends a checksum, so a
// modem line without one was cut short and then terminated: it is refused
// (ChecksumRule::kRequired). A modem accepts host commands without one, so
// the fake modem parses host lines with ChecksumRule::kOptional.
//
// serialize() writes the canonical form, always with the checksum and
// without the line end (append kLineEnd when writing to the port).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "micromodem/nmea/result.h"

namespace acomms::micromodem {

// WHOI's utilities size sentences at 5664 characters; real lines reach
// ~4.2 k (a 2 KiB FDP packet in hex). Longer lines are dropped (§2.3 rule 4).
inline constexpr size_t kMaxLineLength = 8192;
inline constexpr std::string_view kLineEnd = "\r\n";

enum class ChecksumRule { kRequired, kOptional };

enum class ChecksumState {
  kVerified,    // "*HH" present and correct
  kAbsent,      // no "*HH" (accepted only under ChecksumRule::kOptional)
  kUnverified,  // an 8-digit CRC-32 (some MM2 set-ups): present, not checked (§2.3)
};

struct Sentence {
  std::string talker;  // "CC" host → modem, "CA"/"SN" modem → host
  std::string type;    // "CYC", "RXD", ...
  std::vector<std::string> fields;
  ChecksumState checksum = ChecksumState::kVerified;

  std::string address() const { return talker + type; }  // "CACYC"
  bool is(std::string_view address) const;
  // The field numbered as the spec numbers them (from 1); "" past the end.
  std::string_view field(size_t number) const;
  bool operator==(const Sentence&) const = default;
};

// XOR of every byte of `body` (the text strictly between '$' and '*').
uint8_t nmea_checksum(std::string_view body);

// One line, with or without its trailing CR/LF.
Result<Sentence> parse_sentence(std::string_view line,
                                ChecksumRule rule = ChecksumRule::kRequired);

// "$TTSSS,f1,...,fN*HH" (no line end). Throws std::invalid_argument for a
// sentence that cannot be written (an address that is not 2+3 letters or
// digits, a field holding ',', '*', '$' or a non-printable byte): that is
// a programming error, never a property of received input.
std::string serialize(const Sentence& sentence);

}  // namespace acomms::micromodem
