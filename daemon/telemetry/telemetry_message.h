#pragma once
// The bit layout of a telemetry message (DCCL bit order, dccl/bitstream.h).
//
//   kind        1 bit   0 delta, 1 full
//   sequence    4 bits  message count mod 16: the thesis sends no index and
//                       assumes in-order, duplicate-free delivery; this lets
//                       a receiver drop a resent duplicate and notice a gap
//   full:  time of day  17 bits, whole seconds since 00:00 UTC (< 86400)
//          x, y, z      each uniform over the config's region on the
//                       precision grid: ceil(log2(cells)) bits
//          fresh        1 bit: 1 both ends start their statistics afresh
//                       (the sender has none to keep, or the receiver said
//                       it lost them); 0 they carry on, and then
//          continues    1 bit: 1 the position is the next sample of the
//                       stream (a delta could have carried it: both ends
//                       accept it as one, observer and statistics); 0 the
//                       observer re-anchors at it
//          check        8 bits: the low bits of the sender's
//                       StreamPredictor::check() before this full; a
//                       receiver whose own differs does not hold the
//                       sender's statistics and decodes no delta until a
//                       fresh full
//          (The fresh/continues/check bits are new in this layout: a
//          receiver of the earlier one finds bits left over after the
//          position and counts the full undecodable.)
//   delta: x, y, z innovations as one arithmetic codeword (the three axes'
//          symbols in order, then the coder's exact end), so the message
//          ends exactly where the decoder stops and the next field of a
//          frame starts right after it
//
// The time of a delta is the last sample's + tau; a full's is the time of
// day, which the receiver places in its own day (unwrap_time_of_day).

#include <array>
#include <cstdint>

#include "dccl/bitstream.h"
#include "telemetry/observer.h"

namespace acomms::telemetry {

enum class MessageKind : uint8_t { kDelta = 0, kFull = 1 };

inline constexpr unsigned kSequenceBits = 4;
inline constexpr uint32_t kSequenceModulus = 1u << kSequenceBits;
inline constexpr unsigned kHeaderBits = 1 + kSequenceBits;
inline constexpr unsigned kTimeOfDayBits = 17;
inline constexpr int64_t kSecondsPerDay = 86400;
inline constexpr unsigned kStatisticsCheckBits = 8;

// The region on the precision grid: cell i of axis a is min[a] + i.
struct RegionGrid {
  GridPosition min{};
  std::array<uint64_t, kAxes> cells{};
  std::array<unsigned, kAxes> bits{};

  bool contains(const GridPosition& position) const;
};
RegionGrid region_grid(const TelemetryConfig& config);

struct Header {
  MessageKind kind = MessageKind::kDelta;
  uint32_t sequence = 0;
};
void write_header(dccl::BitWriter& out, const Header& header);
Header read_header(dccl::BitReader& in);

struct FullBody {
  int64_t time_of_day_s = 0;
  GridPosition position{};
  bool fresh = true;
  bool continues = false;   // when not fresh
  uint32_t check = 0;       // when not fresh: < 2^kStatisticsCheckBits
};
// Bits a full body takes at most (one that carries the statistics on).
unsigned full_body_bits(const RegionGrid& region);
// position must be inside region, 0 <= time_of_day_s < 86400.
void write_full_body(dccl::BitWriter& out, const RegionGrid& region, const FullBody& body);
// Throws dccl::decode_error for a time or cell outside its range,
// dccl::TruncatedRead when the bits end.
FullBody read_full_body(dccl::BitReader& in, const RegionGrid& region);

// The time congruent to time_s modulo a day that is nearest reference_s.
int64_t unwrap_time_of_day(int64_t time_s, int64_t reference_s);

}  // namespace acomms::telemetry
