#pragma once
// One line from the modem, classified (spec §2's parsing rule): a final
// code, READY, a one-digit SBD result, an information line of a known
// command (+SBDIX/+SBDIXA, +SBDSX, +SBDS, +CSQ), an unsolicited line
// (SBDRING, +CIEV, +AREG), or anything else as text (an IMEI, an echo,
// another command's information) for the command that is waiting.
//
// The modem puts spaces after some colons and commas and not after others
// (`+SBDIX: 0, 10, 1` and `+CSQ:5`), and fields may be negative (MTMSN -1):
// numbers are parsed signed with optional spaces around them. A known
// prefix whose fields do not parse is kMalformed, never a guess.
//
// Thread-safe: pure functions.

#include <cstdint>
#include <string>
#include <string_view>

namespace acomms::iridium {

// +SBDIX / +SBDIXA: the outcome of one session (spec §5.1).
struct SessionResult {
  int mo_status = 0;
  int momsn = 0;
  int mt_status = 0;  // 0 none, 1 received into the MT buffer, 2 error
  int mtmsn = 0;
  int mt_length = 0;
  int mt_queued = 0;
  bool answered_alert = false;  // the line began "+SBDIXA:"
};

// +SBDSX (and +SBDS, which lacks the last two fields): the buffers (§4.5).
struct BufferStatus {
  int mo_flag = 0;
  int momsn = 0;  // the MOMSN the next session will use
  int mt_flag = 0;
  int mtmsn = -1;
  int ra_flag = 0;      // +SBDSX only
  int msg_waiting = 0;  // +SBDSX only
  bool extended = false;
};

// +CIEV:<indicator>,<value>: 0 signal (0..5), 1 service, 2 antenna fault.
struct Indicator {
  int indicator = 0;
  int value = 0;
};

struct AtLine {
  enum class Kind {
    kOk,
    kError,
    kReady,
    kDigit,      // a bare SBD result digit (or a numeric-mode code: the driver decides)
    kSession,    // +SBDIX: / +SBDIXA:
    kStatus,     // +SBDSX: / +SBDS:
    kSignal,     // +CSQ: / +CSQF:
    kIndicator,  // +CIEV:
    kRing,       // SBDRING
    kRegistration,  // +AREG: (unsolicited, mode 2 only)
    kText,       // anything else: information for the waiting command, or an echo
    kMalformed,  // a known prefix whose fields do not parse
  };
  Kind kind = Kind::kText;
  std::string text;  // the line as received, without CR/LF
  int digit = -1;
  SessionResult session;
  BufferStatus status;
  int rssi = -1;
  Indicator indicator;

  // SBDRING, +CIEV and +AREG come whenever the modem likes (spec §2).
  bool unsolicited() const {
    return kind == Kind::kRing || kind == Kind::kIndicator || kind == Kind::kRegistration;
  }
};

// Classifies one non-empty line (without its CR/LF).
AtLine classify_line(std::string_view line);

const char* to_string(AtLine::Kind kind);

}  // namespace acomms::iridium
