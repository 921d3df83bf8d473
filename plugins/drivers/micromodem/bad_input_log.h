#pragma once
// Counts what the modem's port gives that the driver cannot use, and logs
// it once per burst.
//
// The problem: bad input comes in bursts (power-up noise, a gateway
// replaying stale bytes, a loose connector); a warning per line would
// flood the log exactly when a person needs it, and silence would hide a
// failing cable. The decision: every kind is counted (for status and
// tests); a bad line is logged with its reason when none was logged for
// `gap`, the rest of the burst only counted, and the next logged line says
// how many were not logged (a burst is one line; a long one, a line per gap).
//
// Core thread only.

#include <chrono>
#include <cstdint>
#include <map>
#include <string>

#include "core/clock.h"

namespace acomms::drivers::micromodem {

class BadInputLog {
 public:
  BadInputLog(std::string label, std::chrono::system_clock::duration gap = std::chrono::seconds(10))
      : label_(std::move(label)), gap_(gap) {}

  // One bad thing of `kind` ("bad checksum", "unknown sentence", ...).
  void note(const std::string& kind, const std::string& detail, core::Clock::time_point now, uint64_t count = 1);

  uint64_t count(const std::string& kind) const;
  uint64_t total() const { return total_; }
  uint64_t logged() const { return logged_; }
  const std::map<std::string, uint64_t>& counts() const { return counts_; }

 private:
  std::string label_;
  std::chrono::system_clock::duration gap_;
  std::map<std::string, uint64_t> counts_;
  uint64_t total_ = 0;
  uint64_t logged_ = 0;
  uint64_t unlogged_ = 0;
  bool any_ = false;
  core::Clock::time_point last_{};  // when a line was last logged
};

}  // namespace acomms::drivers::micromodem
