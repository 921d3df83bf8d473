// LSB-first bit packing, the DCCL wire order.
//
// A value v of n bits written at stream position p puts bit i of v at stream
// bit p+i, and stream bit k lives in byte k/8 at bit k%8. Both classes work on
// whole values of up to 64 bits so field codecs never handle single bits.
//
// Not thread-safe: a BitWriter or BitReader, and the bytes under it, belong to
// the one encode or decode using it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace acomms::dccl {

// Appends bits to a byte string. Bits of a partially filled last byte that
// have not been written yet are zero, which gives DCCL's zero padding for
// free: align() only has to move the position.
class BitWriter {
 public:
  explicit BitWriter(std::string* out) : out_(out), bit_(out->size() * 8) {}

  // Writes the low n bits of value (n <= 64; higher bits of value are ignored).
  void write(uint64_t value, unsigned n);
  // Writes n zero bits (any n).
  void write_zeros(uint64_t n);
  // Writes whole bytes, 8 bits each in stream order.
  void write_bytes(std::string_view bytes);
  // Pads with zeros up to the next byte boundary.
  void align() { bit_ = (bit_ + 7) / 8 * 8; }

  uint64_t position() const { return bit_; }

 private:
  std::string* out_;
  uint64_t bit_;  // next bit to write, counted from the start of *out_
};

// Thrown by BitReader when the input ends early. Field codecs let it
// propagate; the message codec turns it into an Error naming the field.
struct TruncatedRead {
  uint64_t position;  // bit, relative to the reader's origin, where the read started
  uint64_t needed;    // bits the read wanted
  uint64_t left;      // bits that were left
};

// Reads bits from a byte string; every read is bounds checked.
class BitReader {
 public:
  // Reads data starting at bit `start`; positions in errors count from `origin`.
  explicit BitReader(std::string_view data, uint64_t start = 0, uint64_t origin = 0)
      : data_(data), bit_(start), origin_(origin) {}

  // Reads n bits (n <= 64). Throws TruncatedRead.
  uint64_t read(unsigned n);
  // Reads n whole bytes into out. Throws TruncatedRead.
  void read_bytes(uint64_t n, std::string* out);
  // Skips to the next byte boundary (the bits skipped need not be present).
  void align() { bit_ = (bit_ + 7) / 8 * 8; }
  // Throws TruncatedRead unless n more bits are available.
  void require(uint64_t n) const;

  uint64_t position() const { return bit_; }
  uint64_t remaining() const {
    uint64_t total = uint64_t{data_.size()} * 8;
    return bit_ >= total ? 0 : total - bit_;
  }

 private:
  std::string_view data_;
  uint64_t bit_;
  uint64_t origin_;
};

}  // namespace acomms::dccl
