#pragma once
// The integer arithmetic coder shared by the "dccl.arithmetic" field codec
// (plugins/codecs/arithmetic) and position telemetry (daemon/telemetry): the
// 32-bit coder of Witten, Neal & Cleary ("Arithmetic coding for data
// compression", CACM 1987), with two changes that make a coded field a
// self-delimiting run of bits inside a DCCL message:
//
// - The encoder does not flush a fixed two bits: finish() writes the fewest
//   bits b such that every continuation of b lies inside the final interval
//   (the shortest dyadic interval inside it). After renormalisation the
//   interval straddles 1/2 and spans more than 1/4, so this is at most two
//   bits plus the pending follow bits, and it is exactly the end rule of
//   Schneider (2013) eq. 3.30-3.32 (shared/spec/telemetry.md section 4):
//   [0, 1) -> nothing (with pending bits: 0, then the follow bits);
//   [low, 1) -> 1; [0, high) -> 0; low < 1/4, high >= 1/2 -> 01;
//   low < 1/2, high >= 3/4 -> 10. One tie is ours to break: with low exactly
//   1/4 both 01 and 10 fit in two bits and finish() writes 01 (the lowest
//   block at or above low); the decoder accepts either.
// - The decoder does not preload 32 bits. It keeps the range of values the
//   bits read so far allow (the rest all zeros .. all ones) and reads one more
//   bit only while the two ends of that range decode as different symbols.
//
// Together these make the decoder stop on exactly the last bit the encoder
// wrote, whatever follows it, so the next field or message starts in the
// right place. Coder bits are written most significant first, one per stream
// position (DCCL's LSB-first packing of 1-bit values).
//
// Threads: coders share nothing; an Encoder, a Decoder and a table being
// incremented belong to the one caller coding with them, while a table that is
// only read may be shared.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dccl/bitstream.h"

namespace acomms::dccl::arith {

// Code values are 32 bits: the interval [low, high] lives in [0, 2^32 - 1].
inline constexpr uint64_t kTop = (uint64_t{1} << 32) - 1;
inline constexpr uint64_t kQuarter = uint64_t{1} << 30;
inline constexpr uint64_t kHalf = 2 * kQuarter;
inline constexpr uint64_t kThreeQuarters = 3 * kQuarter;
// Largest total frequency. After renormalisation the interval spans more
// than a quarter of the code space, so every symbol with frequency >= 1 still
// gets a non-empty sub-interval.
inline constexpr uint64_t kMaxTotalFrequency = kQuarter - 1;

// Cumulative frequencies of an alphabet, symbol s covering
// [low(s), high(s)) of [0, total()).
class FrequencyTable {
 public:
  explicit FrequencyTable(const std::vector<uint32_t>& frequencies);

  size_t size() const { return cumulative_.size() - 1; }
  uint64_t total() const { return cumulative_.back(); }
  uint64_t low(size_t symbol) const { return cumulative_[symbol]; }
  uint64_t high(size_t symbol) const { return cumulative_[symbol + 1]; }
  uint64_t frequency(size_t symbol) const { return high(symbol) - low(symbol); }
  // The symbol whose range holds count (count < total()); never a symbol of
  // frequency 0.
  size_t find(uint64_t count) const;
  // Adaptive models: one more occurrence of symbol.
  void increment(size_t symbol);

 private:
  std::vector<uint64_t> cumulative_;  // cumulative_[s] = sum of frequencies before s
};

class Encoder {
 public:
  explicit Encoder(dccl::BitWriter& out) : out_(out) {}

  // Narrows the interval to symbol's share of it. symbol must have a
  // non-zero frequency.
  void encode(const FrequencyTable& table, size_t symbol);
  // Writes the bits that pin the final interval. Call once, at the end.
  void finish();

 private:
  void emit(unsigned bit);

  dccl::BitWriter& out_;
  uint64_t low_ = 0;
  uint64_t high_ = kTop;
  uint64_t pending_ = 0;  // bits owed after the next emitted bit (opposite value)
};

class Decoder {
 public:
  explicit Decoder(dccl::BitReader& in) : in_(in) {}

  // The next symbol. Reads only the bits needed to be sure of it; a read
  // past the end throws dccl::TruncatedRead.
  size_t decode(const FrequencyTable& table);

 private:
  uint64_t count_of(const FrequencyTable& table, uint64_t value) const;

  dccl::BitReader& in_;
  uint64_t low_ = 0;
  uint64_t high_ = kTop;
  // The code value is somewhere in [min_, max_]: the bits read so far
  // followed by all zeros / all ones. unknown_ low bits are not read yet.
  uint64_t min_ = 0;
  uint64_t max_ = kTop;
  unsigned unknown_ = 32;
};

}  // namespace acomms::dccl::arith
