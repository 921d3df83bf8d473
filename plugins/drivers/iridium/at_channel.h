#pragma once
// One AT command at a time, and what answers it (spec §2, §7: "only one
// command is outstanding at a time; unsolicited lines are handled in every
// state").
//
// The problem: the modem's answers are lines that only make sense against
// the command that is waiting (a "0" is an SBD result after AT+SBDD0 and
// the numeric-mode OK after AT), mixed with lines that belong to no command
// (SBDRING, +CIEV), with our own echo after a modem reset, and with one
// binary block. The decision: the channel owns the command in flight, its
// deadline (a scheduler timer), and the reader (at/at_reader.h); it hands
// the driver one Reply per command and every unsolicited line as it comes.
// It decides nothing else.
//
// How a command ends, by what it expects:
//   kFinal        OK or ERROR. A bare digit instead (the modem fell back to
//                 numeric codes: 0 = OK, 4 = ERROR) ends it too and is
//                 flagged (numeric_seen) so the driver can restore ATV1.
//   kResult       an SBD result digit, then OK; result 1 after +SBDWB data
//                 has no OK (a firmware quirk, spec §4.1) and ends at once.
//   kReady        READY; a digit instead (3: wrong size, sent in place of
//                 READY by some firmware) ends it with that digit.
//   kBlock        the MT block (the reader is switched to it), then OK.
// A line equal to the command's own text is its echo: skipped and counted
// (echoes_seen), since echo returning means the modem lost its settings.
//
// Thread-safety: none; the driver's (core thread).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/scheduler.h"
#include "iridium/at/at_reader.h"
#include "iridium/iridium_settings.h"

namespace acomms::drivers::iridium {

using ::acomms::iridium::AtLine;
using ::acomms::iridium::AtReader;
using ::acomms::iridium::MtBlock;

class AtChannel {
 public:
  enum class Expect { kFinal, kResult, kReady, kBlock };

  struct Reply {
    enum class End { kOk, kError, kReady, kDigit, kTimeout };
    End end = End::kTimeout;
    std::vector<AtLine> lines;  // information lines of this command, in order
    int digit = -1;             // the SBD result digit, if one came
    std::optional<MtBlock> block;
    size_t bad_block_length = 0;  // a block abandoned for its length (0: none)
    bool ok() const { return end == End::kOk; }
  };
  using Done = std::function<void(Reply reply)>;
  using Write = std::function<bool(std::string_view bytes)>;
  using Unsolicited = std::function<void(const AtLine& line)>;

  struct Counters {
    uint64_t commands = 0;
    uint64_t timeouts = 0;
    uint64_t echoes = 0;
    uint64_t malformed = 0;  // a known answer whose fields did not parse
    uint64_t stray = 0;      // a line while no command waited
  };

  AtChannel(core::Scheduler& scheduler, Write write, Unsolicited unsolicited);
  ~AtChannel();
  AtChannel(const AtChannel&) = delete;
  AtChannel& operator=(const AtChannel&) = delete;

  // Writes `bytes` ("AT+SBDIX\r", or the binary block after READY) and
  // calls `done` once: with the answer, or kTimeout after `timeout`. A
  // write the port refuses ends as kTimeout at once (in a scheduler task).
  // `echo` is the text whose return is an echo ("" for binary data).
  void send(std::string bytes, std::string echo, Expect expect, Duration timeout, Done done);
  bool busy() const { return pending_.has_value(); }
  // Bytes from the modem.
  void on_bytes(std::string_view bytes);
  // Forgets the command in flight without calling its `done`; input keeps
  // its place (a line half received is still the modem's).
  void cancel();
  // cancel(), and forgets partial input too (the port was lost or the
  // driver stops: what comes next starts afresh).
  void abort();

  // Echoes or numeric codes seen since the last clear_flags().
  bool echo_seen() const { return echo_seen_; }
  bool numeric_seen() const { return numeric_seen_; }
  void clear_flags() { echo_seen_ = numeric_seen_ = false; }
  const Counters& counters() const { return counters_; }
  const AtReader::Counters& reader_counters() const { return reader_.counters(); }

 private:
  struct Pending {
    std::string echo;
    Expect expect;
    Done done;
    Reply reply;
    core::Scheduler::TaskId timer = 0;
  };
  void on_line(const AtLine& line);
  void finish(Reply::End end);
  void arm(Duration timeout);

  core::Scheduler& scheduler_;
  Write write_;
  Unsolicited unsolicited_;
  AtReader reader_;
  std::optional<Pending> pending_;
  uint64_t generation_ = 0;
  bool echo_seen_ = false;
  bool numeric_seen_ = false;
  Counters counters_;
};

}  // namespace acomms::drivers::iridium
