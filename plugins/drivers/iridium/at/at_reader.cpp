#include "iridium/at/at_reader.h"

#include "iridium/at/sbd_binary.h"

namespace acomms::iridium {

std::vector<AtEvent> AtReader::push(std::string_view bytes) {
  std::vector<AtEvent> out;
  for (char c : bytes) {
    if (mode_ == Mode::kBlockBody) {
      block_byte(c, out);
    } else if (mode_ == Mode::kBlockWait && !in_line_) {
      auto u = static_cast<unsigned char>(c);
      if (c == '\r' || c == '\n') continue;  // padding before the length
      if (u <= 0x01) {
        mode_ = Mode::kBlockBody;
        block_byte(c, out);
      } else {
        in_line_ = true;  // an unsolicited line or an echo, before the block
        line_byte(c, out);
      }
    } else {
      line_byte(c, out);
    }
  }
  return out;
}

void AtReader::line_byte(char c, std::vector<AtEvent>& out) {
  if (c == '\r' || c == '\n') return end_line(out);
  auto u = static_cast<unsigned char>(c);
  if (u < 0x20 || u > 0x7E) line_garbled_ = true;
  if (line_.size() >= kMaxLineBytes) {
    line_overlong_ = true;  // kept no further: memory stays bounded
    return;
  }
  line_.push_back(c);
}

void AtReader::end_line(std::vector<AtEvent>& out) {
  in_line_ = false;
  if (line_overlong_) {
    ++counters_.overlong_lines;
  } else if (line_garbled_) {
    ++counters_.garbled_lines;
  } else if (!line_.empty()) {
    ++counters_.lines;
    AtEvent event;
    event.line = classify_line(line_);
    out.push_back(std::move(event));
  }
  line_.clear();
  line_garbled_ = false;
  line_overlong_ = false;
}

void AtReader::block_byte(char c, std::vector<AtEvent>& out) {
  block_.push_back(c);
  if (block_.size() == 2) {
    block_length_ = static_cast<size_t>(static_cast<unsigned char>(block_[0])) << 8 |
                    static_cast<unsigned char>(block_[1]);
    if (block_length_ > kMaxMtBytes) {
      ++counters_.bad_lengths;
      AtEvent event;
      event.kind = AtEvent::Kind::kBadBlock;
      event.bad_length = block_length_;
      out.push_back(std::move(event));
      block_.clear();
      mode_ = Mode::kLines;
    }
    return;
  }
  if (block_.size() < block_length_ + 4) return;
  AtEvent event;
  event.kind = AtEvent::Kind::kBlock;
  event.block.payload = block_.substr(2, block_length_);
  event.block.checksum = static_cast<uint16_t>(static_cast<unsigned char>(block_[block_length_ + 2]) << 8 |
                                               static_cast<unsigned char>(block_[block_length_ + 3]));
  event.block.checksum_ok = event.block.checksum == sbd_checksum(event.block.payload);
  ++counters_.blocks;
  if (!event.block.checksum_ok) ++counters_.bad_checksums;
  out.push_back(std::move(event));
  block_.clear();
  mode_ = Mode::kLines;
}

void AtReader::expect_binary() {
  block_.clear();
  // A line already begun finishes first (it cannot be the block).
  in_line_ = !line_.empty() || line_garbled_ || line_overlong_;
  mode_ = Mode::kBlockWait;
}

void AtReader::cancel_binary() {
  block_.clear();
  in_line_ = false;
  mode_ = Mode::kLines;
}

void AtReader::reset() {
  cancel_binary();
  line_.clear();
  line_garbled_ = false;
  line_overlong_ = false;
}

}  // namespace acomms::iridium
