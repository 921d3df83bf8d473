#include "sim/sim_envelope.h"

#include <bit>
#include <cmath>
#include <cstring>

namespace acomms::drivers {

namespace {

constexpr char kMagic[4] = {'A', 'S', 'I', 'M'};
constexpr uint8_t kVersion = 1;
constexpr size_t kHeaderSize = 4 + 1 + 4 + 3 * 8 + 8 + 8 + 4;
// Longer than any Micro-Modem packet by far; anything beyond is garbage.
constexpr std::chrono::nanoseconds kMaxDuration = std::chrono::minutes(10);
// Farther than any acoustic path; also keeps distances and delays finite.
constexpr double kMaxCoordinate = 1e7;  // m
// 2100-01-01T00:00:00Z: with a day of travel and kMaxDuration added, still
// far from the int64 nanosecond limit (2262).
constexpr int64_t kLatestStartNs = 4'102'444'800LL * 1'000'000'000LL;
constexpr double kMaxTravelSeconds = 86'400;

void put_u32(std::string* out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out->push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void put_u64(std::string* out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out->push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
uint32_t get_u32(const unsigned char* p) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= uint32_t{p[i]} << (8 * i);
  return v;
}
uint64_t get_u64(const unsigned char* p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= uint64_t{p[i]} << (8 * i);
  return v;
}

}  // namespace

double distance(const SimPosition& a, const SimPosition& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

std::string encode(const SimEnvelope& e) {
  std::string body = e.transmission.SerializeAsString();
  std::string out(kMagic, sizeof kMagic);
  out.push_back(static_cast<char>(kVersion));
  put_u32(&out, static_cast<uint32_t>(e.sender));
  put_u64(&out, std::bit_cast<uint64_t>(e.position.x));
  put_u64(&out, std::bit_cast<uint64_t>(e.position.y));
  put_u64(&out, std::bit_cast<uint64_t>(e.position.z));
  put_u64(&out, static_cast<uint64_t>(
                    std::chrono::duration_cast<std::chrono::nanoseconds>(e.start.time_since_epoch()).count()));
  put_u64(&out, static_cast<uint64_t>(e.duration.count()));
  put_u32(&out, static_cast<uint32_t>(body.size()));
  out += body;
  return out;
}

std::optional<SimEnvelope> decode_envelope(std::string_view bytes, std::string* error) {
  auto fail = [&](const std::string& why) -> std::optional<SimEnvelope> {
    if (error) *error = why;
    return std::nullopt;
  };
  if (bytes.size() < kHeaderSize) {
    return fail(std::to_string(bytes.size()) + " bytes, shorter than an envelope header");
  }
  if (std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) return fail("not a sim envelope (bad magic)");
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  if (p[4] != kVersion) return fail("envelope version " + std::to_string(p[4]) + ", expected 1");
  SimEnvelope e;
  e.sender = static_cast<int32_t>(get_u32(p + 5));
  e.position.x = std::bit_cast<double>(get_u64(p + 9));
  e.position.y = std::bit_cast<double>(get_u64(p + 17));
  e.position.z = std::bit_cast<double>(get_u64(p + 25));
  auto start_ns = static_cast<int64_t>(get_u64(p + 33));
  e.duration = std::chrono::nanoseconds(static_cast<int64_t>(get_u64(p + 41)));
  uint32_t length = get_u32(p + 49);
  if (e.sender < 0) return fail("negative sender id " + std::to_string(e.sender));
  for (double coordinate : {e.position.x, e.position.y, e.position.z}) {
    // Also false for NaN.
    if (!(std::fabs(coordinate) <= kMaxCoordinate)) {
      return fail("position is not finite or farther than 10,000 km");
    }
  }
  if (start_ns < 0 || start_ns > kLatestStartNs) {
    return fail("start " + std::to_string(start_ns) + " ns is not between 1970 and 2100");
  }
  if (e.duration.count() <= 0 || e.duration > kMaxDuration) {
    return fail("duration " + std::to_string(e.duration.count()) + " ns is out of range");
  }
  if (length != bytes.size() - kHeaderSize) {
    return fail("transmission length " + std::to_string(length) + " does not match the " +
                std::to_string(bytes.size() - kHeaderSize) + " bytes that follow");
  }
  e.start = core::Clock::time_point(std::chrono::duration_cast<core::Clock::time_point::duration>(
      std::chrono::nanoseconds(start_ns)));
  if (!e.transmission.ParseFromArray(bytes.data() + kHeaderSize, static_cast<int>(length))) {
    return fail("transmission does not parse");
  }
  return e;
}

std::optional<SimHearing> hearing(const SimEnvelope& envelope, const SimPosition& at, double sound_speed_mps) {
  SimHearing heard;
  heard.range_m = distance(at, envelope.position);
  const double travel_s = heard.range_m / sound_speed_mps;
  if (!(travel_s >= 0 && travel_s <= kMaxTravelSeconds)) return std::nullopt;
  heard.start = envelope.start + std::chrono::duration_cast<core::Clock::time_point::duration>(
                                     std::chrono::nanoseconds(std::llround(travel_s * 1e9)));
  heard.end = heard.start + std::chrono::duration_cast<core::Clock::time_point::duration>(envelope.duration);
  return heard;
}

}  // namespace acomms::drivers
