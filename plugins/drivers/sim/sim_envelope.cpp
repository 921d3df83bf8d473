#include "sim/sim_envelope.h"

#include <bit>
#include <cmath>
#include <cstring>

#include "util/little_endian.h"

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

}  // namespace

double distance(const SimPosition& a, const SimPosition& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

std::string encode(const SimEnvelope& e) {
  std::string body = e.transmission.SerializeAsString();
  std::string out(kMagic, sizeof kMagic);
  out.push_back(static_cast<char>(kVersion));
  util::put_le(&out, static_cast<uint32_t>(e.sender), 4);
  util::put_le(&out, std::bit_cast<uint64_t>(e.position.x), 8);
  util::put_le(&out, std::bit_cast<uint64_t>(e.position.y), 8);
  util::put_le(&out, std::bit_cast<uint64_t>(e.position.z), 8);
  util::put_le(&out,
               static_cast<uint64_t>(
                   std::chrono::duration_cast<std::chrono::nanoseconds>(e.start.time_since_epoch()).count()),
               8);
  util::put_le(&out, static_cast<uint64_t>(e.duration.count()), 8);
  util::put_le(&out, static_cast<uint32_t>(body.size()), 4);
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
  e.sender = static_cast<int32_t>(static_cast<uint32_t>(util::load_le(p + 5, 4)));
  e.position.x = std::bit_cast<double>(util::load_le(p + 9, 8));
  e.position.y = std::bit_cast<double>(util::load_le(p + 17, 8));
  e.position.z = std::bit_cast<double>(util::load_le(p + 25, 8));
  auto start_ns = static_cast<int64_t>(util::load_le(p + 33, 8));
  e.duration = std::chrono::nanoseconds(static_cast<int64_t>(util::load_le(p + 41, 8)));
  uint32_t length = static_cast<uint32_t>(util::load_le(p + 49, 4));
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
