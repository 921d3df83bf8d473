#pragma once
// Cuts the modem's byte stream into lines, the way WHOI's own C readers do
// (spec §2.3 rules 1-4):
//   1. bytes before a '$' are noise (power-up, binary garbage, the second
//      half of a sentence after the port opened): discarded and counted;
//   2. a '$' inside a line means that line was cut short: it is dropped
//      (counted as truncated) and a new line starts at the new '$';
//   3. CR or LF ends a line; empty lines do not exist here;
//   4. a line longer than the bound is dropped up to its line end (or the
//      next '$') and counted, never accumulated: memory stays bounded
//      whatever the input.
// Serial ports and serial-to-TCP gateways deliver arbitrary chunks (§10
// quirk 20), so push() takes any split of the stream and yields the same
// lines. The lines keep everything from '$' to before CR/LF, unchecked:
// parse_sentence() judges them.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {

class LineFramer {
 public:
  struct Counters {
    uint64_t lines = 0;            // lines yielded
    uint64_t noise_bytes = 0;      // discarded outside any line
    uint64_t truncated_lines = 0;  // cut short by a new '$'
    uint64_t overlong_lines = 0;   // longer than max_line_length, dropped
  };

  explicit LineFramer(size_t max_line_length = kMaxLineLength);

  // Appends `bytes` and returns the lines they complete, in order.
  std::vector<std::string> push(std::string_view bytes);
  // Forgets a partial line (e.g. after a reconnect: stale bytes, §10 quirk 20).
  void reset();

  const Counters& counters() const { return counters_; }
  // Bytes held for the line in progress (never more than max_line_length).
  size_t buffered() const { return line_.size(); }

 private:
  enum class State { kSeeking, kInLine, kDiscarding };
  size_t max_line_length_;
  State state_ = State::kSeeking;
  std::string line_;
  Counters counters_;
};

}  // namespace acomms::micromodem
