#pragma once
// Cuts the modem's byte stream into classified lines (at_line.h) and, when
// the host has asked for the MT buffer, into the one binary block that
// breaks the line rule (spec §4.3).
//
// The problem: the serial side is a text protocol with one binary answer,
// and anything may arrive at any time: echo (it comes back on after a modem
// reset), unsolicited lines (SBDRING, +CIEV) even between AT+SBDRB and its
// length bytes, power-up garbage, and chunks cut anywhere (a serial-to-TCP
// gateway). The decision: a small state machine that owns no policy. In
// line mode CR or LF ends a line; empty lines are dropped; a line with
// bytes outside printable ASCII, or longer than kMaxLineBytes, is dropped
// and counted (memory stays bounded whatever arrives). After
// expect_binary() the reader waits for the block: CR/LF there are padding;
// a first byte of 0x00 or 0x01 starts the 2-byte length (an MT is at most
// 270 = 0x010E bytes, so the length's first byte is nothing else); any
// other byte starts a line (an unsolicited line, or our own echo) that is
// read to its end and yielded, and the wait goes on. A length over 270 is
// reported and the reader returns to line mode.
//
// Invariant: cutting the stream into chunks changes nothing (the fuzz
// target checks it).
//
// Thread-safety: none; one reader per port, used on one thread.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "iridium/at/at_line.h"

namespace acomms::iridium {

inline constexpr size_t kMaxLineBytes = 512;

// The MT buffer as AT+SBDRB sent it.
struct MtBlock {
  std::string payload;
  uint16_t checksum = 0;     // as sent
  bool checksum_ok = false;  // matches sbd_checksum(payload)
};

struct AtEvent {
  enum class Kind {
    kLine,
    kBlock,     // a complete binary block (check checksum_ok)
    kBadBlock,  // a length over the MT limit: the block was abandoned
  };
  Kind kind = Kind::kLine;
  AtLine line;      // kLine
  MtBlock block;    // kBlock
  size_t bad_length = 0;  // kBadBlock
};

class AtReader {
 public:
  struct Counters {
    uint64_t lines = 0;           // lines yielded
    uint64_t garbled_lines = 0;   // dropped: bytes outside printable ASCII
    uint64_t overlong_lines = 0;  // dropped: longer than kMaxLineBytes
    uint64_t blocks = 0;          // binary blocks yielded
    uint64_t bad_checksums = 0;   // of those, with a checksum that did not match
    uint64_t bad_lengths = 0;     // blocks abandoned for their length
  };

  // Appends `bytes`; returns the events they complete, in order.
  std::vector<AtEvent> push(std::string_view bytes);
  // The next block is the MT buffer (AT+SBDRB was just written).
  void expect_binary();
  // Back to line mode, dropping a partial block (a read that timed out).
  void cancel_binary();
  bool expecting_binary() const { return mode_ != Mode::kLines; }
  // Forgets everything partial (a reconnected port).
  void reset();
  // Bytes held for an unfinished line or block: bounded by
  // kMaxLineBytes + kMaxMtBytes + 4.
  size_t buffered() const { return line_.size() + block_.size(); }
  const Counters& counters() const { return counters_; }

 private:
  enum class Mode { kLines, kBlockWait, kBlockBody };
  void line_byte(char c, std::vector<AtEvent>& out);
  void end_line(std::vector<AtEvent>& out);
  void block_byte(char c, std::vector<AtEvent>& out);

  Mode mode_ = Mode::kLines;
  std::string line_;
  bool line_garbled_ = false;
  bool line_overlong_ = false;
  bool in_line_ = false;  // kBlockWait: reading a line that came before the block
  std::string block_;     // length bytes, payload, checksum as they come
  size_t block_length_ = 0;
  Counters counters_;
};

}  // namespace acomms::iridium
