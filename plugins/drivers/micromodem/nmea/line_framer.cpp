#include "micromodem/nmea/line_framer.h"

namespace acomms::micromodem {

LineFramer::LineFramer(size_t max_line_length) : max_line_length_(max_line_length) {
  line_.reserve(max_line_length_ < 1024 ? max_line_length_ : 1024);
}

void LineFramer::reset() {
  line_.clear();
  state_ = State::kSeeking;
}

std::vector<std::string> LineFramer::push(std::string_view bytes) {
  std::vector<std::string> lines;
  for (char c : bytes) {
    if (c == '$') {
      if (state_ == State::kInLine) ++counters_.truncated_lines;
      // A '$' also ends the discarding of an over-long line: a sentence
      // never holds one, so it is the best place to resynchronise.
      line_.assign(1, '$');
      state_ = State::kInLine;
      continue;
    }
    bool line_end = c == '\r' || c == '\n';
    switch (state_) {
      case State::kSeeking:
        if (!line_end) ++counters_.noise_bytes;
        break;
      case State::kDiscarding:
        if (line_end) state_ = State::kSeeking;
        break;
      case State::kInLine:
        if (line_end) {
          lines.push_back(std::move(line_));
          line_.clear();
          ++counters_.lines;
          state_ = State::kSeeking;
        } else if (line_.size() >= max_line_length_) {
          ++counters_.overlong_lines;
          line_.clear();
          state_ = State::kDiscarding;
        } else {
          line_ += c;
        }
        break;
    }
  }
  return lines;
}

}  // namespace acomms::micromodem
