#include "acoustic_packet.h"

#include <cmath>
#include <sstream>

#include "micromodem/nmea/hex.h"

namespace acomms::fake_micromodem {
namespace {

constexpr std::string_view kMagic = "FAKEMM1";
constexpr size_t kMaxFrames = 16;  // an FDP packet is one frame of up to 2 KiB

bool fail(std::string* error, std::string text) {
  if (error) *error = std::move(text);
  return false;
}

bool parse_frames(std::istringstream& in, AcousticPacket& packet, std::string* error) {
  std::string acked;
  if (!(in >> acked)) return fail(error, "no acked-frames field");
  if (acked != "-") {
    std::istringstream list(acked);
    std::string item;
    while (std::getline(list, item, ',')) {
      int frame = 0;
      try {
        frame = std::stoi(item);
      } catch (...) {
        return fail(error, "acked frame '" + item + "' is not a number");
      }
      if (frame < 1 || frame > static_cast<int>(kMaxFrames)) return fail(error, "acked frame out of range");
      packet.acked_frames.push_back(frame);
    }
  }
  std::string item;
  while (in >> item) {
    if (packet.frames.size() == kMaxFrames) return fail(error, "too many frames");
    if (item.size() < 2 || (item[0] != '0' && item[0] != '1') || item[1] != ':') {
      return fail(error, "frame '" + item.substr(0, 20) + "' is not <ack>:<hex>");
    }
    auto bytes = micromodem::hex_decode(std::string_view(item).substr(2));
    if (!bytes) return fail(error, "frame: " + bytes.error().text);
    packet.frames.push_back(DataFrame{item[0] == '1', *bytes});
  }
  return true;
}

}  // namespace

double distance(const Position& a, const Position& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

std::string encode(const WaterDatagram& d) {
  std::ostringstream out;
  out.precision(17);
  const AcousticPacket& p = d.packet;
  out << kMagic << ' ' << d.from.x << ' ' << d.from.y << ' ' << d.from.z << ' '
      << std::llround(d.air_seconds * 1000) << ' ' << static_cast<int>(p.kind) << ' ' << p.rate
      << ' ' << p.source << ' ' << p.destination << ' ' << (p.ack ? 1 : 0) << ' '
      << p.frames_wanted << ' ';
  if (p.acked_frames.empty()) out << '-';
  for (size_t i = 0; i < p.acked_frames.size(); ++i) out << (i ? "," : "") << p.acked_frames[i];
  for (const DataFrame& frame : p.frames) {
    out << ' ' << (frame.ack ? '1' : '0') << ':' << micromodem::hex_encode(frame.bytes);
  }
  return out.str();
}

std::optional<WaterDatagram> decode_datagram(std::string_view text, std::string* error) {
  std::istringstream in{std::string(text)};
  std::string magic;
  WaterDatagram d;
  long long air_ms = 0;
  int kind = 0, ack = 0;
  AcousticPacket& p = d.packet;
  if (!(in >> magic) || magic != kMagic) {
    fail(error, "not a fake-modem datagram");
    return std::nullopt;
  }
  if (!(in >> d.from.x >> d.from.y >> d.from.z >> air_ms >> kind >> p.rate >> p.source >>
        p.destination >> ack >> p.frames_wanted)) {
    fail(error, "datagram header is incomplete");
    return std::nullopt;
  }
  bool finite = std::isfinite(d.from.x) && std::isfinite(d.from.y) && std::isfinite(d.from.z);
  if (!finite || air_ms < 0 || air_ms > 60'000 || kind < 0 || kind > static_cast<int>(PacketKind::kFdp) || p.rate < 0 ||
      p.rate > 6 || p.source < 0 || p.source > 127 || p.destination < 0 || p.destination > 127 ||
      ack < 0 || ack > 1 || p.frames_wanted < 0 || p.frames_wanted > 8) {
    fail(error, "datagram header is out of range");
    return std::nullopt;
  }
  d.air_seconds = static_cast<double>(air_ms) / 1000;
  p.kind = static_cast<PacketKind>(kind);
  p.ack = ack == 1;
  if (!parse_frames(in, p, error)) return std::nullopt;
  return d;
}

}  // namespace acomms::fake_micromodem
