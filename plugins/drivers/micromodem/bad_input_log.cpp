#include "micromodem/bad_input_log.h"

#include <spdlog/spdlog.h>

namespace acomms::drivers::micromodem {

void BadInputLog::note(const std::string& kind, const std::string& detail, core::Clock::time_point now,
                       uint64_t count) {
  if (count == 0) return;
  counts_[kind] += count;
  total_ += count;
  // At most one line per gap: a burst is one line, a long one a line per gap.
  bool log_now = !any_ || now - last_ >= gap_;
  if (!log_now) {
    unlogged_ += count;
    return;
  }
  any_ = true;
  last_ = now;
  ++logged_;
  if (unlogged_ > 0) {
    spdlog::warn("{}: {}: {} ({} more bad input(s) since the last report were only counted)", label_, kind, detail,
                 unlogged_);
  } else {
    spdlog::warn("{}: {}: {}", label_, kind, detail);
  }
  unlogged_ = count - 1;
}

uint64_t BadInputLog::count(const std::string& kind) const {
  auto it = counts_.find(kind);
  return it == counts_.end() ? 0 : it->second;
}

}  // namespace acomms::drivers::micromodem
