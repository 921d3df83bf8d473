#include "telemetry/telemetry_message.h"

#include <cmath>
#include <string>

#include "dccl/error.h"
#include "telemetry/deterministic_math.h"

namespace acomms::telemetry {
namespace {

unsigned bits_for(uint64_t cells) {
  unsigned bits = 0;
  while (bits < 64 && (uint64_t{1} << bits) < cells) ++bits;
  return bits;
}

}  // namespace

bool RegionGrid::contains(const GridPosition& position) const {
  for (int axis = 0; axis < kAxes; ++axis) {
    if (position[axis] < min[axis]) return false;
    if (static_cast<uint64_t>(position[axis] - min[axis]) >= cells[axis]) return false;
  }
  return true;
}

RegionGrid region_grid(const TelemetryConfig& config) {
  RegionGrid region;
  for (int axis = 0; axis < kAxes; ++axis) {
    region.min[axis] = static_cast<int64_t>(std::ceil(config.region_min_m[axis] / config.precision_m));
    const int64_t max = static_cast<int64_t>(std::floor(config.region_max_m[axis] / config.precision_m));
    region.cells[axis] = static_cast<uint64_t>(max - region.min[axis] + 1);
    region.bits[axis] = bits_for(region.cells[axis]);
  }
  return region;
}

void write_header(dccl::BitWriter& out, const Header& header) {
  out.write(static_cast<uint64_t>(header.kind), 1);
  out.write(header.sequence % kSequenceModulus, kSequenceBits);
}

Header read_header(dccl::BitReader& in) {
  Header header;
  header.kind = in.read(1) == 1 ? MessageKind::kFull : MessageKind::kDelta;
  header.sequence = static_cast<uint32_t>(in.read(kSequenceBits));
  return header;
}

unsigned full_body_bits(const RegionGrid& region) {
  return kTimeOfDayBits + region.bits[0] + region.bits[1] + region.bits[2] + 2 + kStatisticsCheckBits;
}

void write_full_body(dccl::BitWriter& out, const RegionGrid& region, const FullBody& body) {
  out.write(static_cast<uint64_t>(body.time_of_day_s), kTimeOfDayBits);
  for (int axis = 0; axis < kAxes; ++axis)
    out.write(static_cast<uint64_t>(body.position[axis] - region.min[axis]), region.bits[axis]);
  out.write(body.fresh ? 1 : 0, 1);
  if (body.fresh) return;
  out.write(body.continues ? 1 : 0, 1);
  out.write(body.check & ((1u << kStatisticsCheckBits) - 1), kStatisticsCheckBits);
}

FullBody read_full_body(dccl::BitReader& in, const RegionGrid& region) {
  FullBody body;
  body.time_of_day_s = static_cast<int64_t>(in.read(kTimeOfDayBits));
  if (body.time_of_day_s >= kSecondsPerDay)
    throw dccl::decode_error("telemetry full transmission: time of day " +
                             std::to_string(body.time_of_day_s) + " s is not below 86400");
  for (int axis = 0; axis < kAxes; ++axis) {
    const uint64_t cell = in.read(region.bits[axis]);
    if (cell >= region.cells[axis])
      throw dccl::decode_error("telemetry full transmission: axis " + std::to_string(axis) + " cell " +
                               std::to_string(cell) + " is outside the region's " +
                               std::to_string(region.cells[axis]) + " cells");
    body.position[axis] = region.min[axis] + static_cast<int64_t>(cell);
  }
  body.fresh = in.read(1) == 1;
  if (!body.fresh) {
    body.continues = in.read(1) == 1;
    body.check = static_cast<uint32_t>(in.read(kStatisticsCheckBits));
  }
  return body;
}

int64_t unwrap_time_of_day(int64_t time_s, int64_t reference_s) {
  const int64_t offset = ((time_s - reference_s) % kSecondsPerDay + kSecondsPerDay) % kSecondsPerDay;
  return offset <= kSecondsPerDay / 2 ? reference_s + offset : reference_s + offset - kSecondsPerDay;
}

}  // namespace acomms::telemetry
