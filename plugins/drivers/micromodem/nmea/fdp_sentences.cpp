#include "micromodem/nmea/fdp_sentences.h"

#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/field_reader.h"
#include "micromodem/nmea/hex.h"

namespace acomms::micromodem {

namespace {

constexpr int kMaxFdpFrames = 64;

std::string frame_list(const std::vector<FdpFrame>& frames) {
  std::string text;
  for (const FdpFrame& frame : frames) {
    if (!text.empty()) text += ';';
    text += (frame.crc_ok ? "1;" : "0;") + std::to_string(frame.data.size()) + ";" + hex_encode(frame.data);
  }
  return text;
}

// "<crc>;<n>;<hex>[;<crc>;<n>;<hex>...]" or "" (no frames).
Result<std::vector<FdpFrame>> parse_frame_list(std::string_view text, const std::string& where) {
  std::vector<FdpFrame> frames;
  if (text.empty()) return frames;
  std::vector<std::string_view> parts;
  size_t at = 0;
  while (true) {
    size_t end = text.find(';', at);
    parts.push_back(text.substr(at, end == std::string_view::npos ? std::string_view::npos : end - at));
    if (end == std::string_view::npos) break;
    at = end + 1;
  }
  if (parts.size() % 3 != 0) {
    return Error{ErrorKind::kBadField, where + " has " + std::to_string(parts.size()) +
                                           " ';'-separated parts, not triplets <crc>;<nbytes>;<data>"};
  }
  if (parts.size() / 3 > kMaxFdpFrames) {
    return Error{ErrorKind::kBadField, where + " has more than " + std::to_string(kMaxFdpFrames) + " frames"};
  }
  for (size_t i = 0; i < parts.size(); i += 3) {
    FdpFrame frame;
    if (parts[i] != "0" && parts[i] != "1") {
      return Error{ErrorKind::kBadField, where + " frame " + std::to_string(i / 3 + 1) + " crc '" +
                                             std::string(parts[i]) + "' is not 0 or 1"};
    }
    frame.crc_ok = parts[i] == "1";
    size_t declared = 0;
    if (parts[i + 1].empty() || parts[i + 1].size() > 5 ||
        parts[i + 1].find_first_not_of("0123456789") != std::string_view::npos) {
      return Error{ErrorKind::kBadField, where + " frame " + std::to_string(i / 3 + 1) + " length '" +
                                             std::string(parts[i + 1]) + "' is not a number of bytes"};
    }
    declared = std::stoul(std::string(parts[i + 1]));
    Result<std::string> bytes = hex_decode(parts[i + 2]);
    if (!bytes) return Error{ErrorKind::kBadField, where + " frame " + std::to_string(i / 3 + 1) + ": " + bytes.error().text};
    if (bytes->size() != declared) {
      return Error{ErrorKind::kBadField, where + " frame " + std::to_string(i / 3 + 1) + " says " +
                                             std::to_string(declared) + " bytes but carries " +
                                             std::to_string(bytes->size())};
    }
    frame.data = std::move(*bytes);
    frames.push_back(std::move(frame));
  }
  return frames;
}

}  // namespace

int fdp_max_data_bytes(int rate) {
  switch (rate) {
    case 1: return 192;
    case 3: return 512;
    case 5: return 2048;
    default: return 0;
  }
}

double fdp_packet_air_s(int rate) {
  switch (rate) {
    case 1: return 1.574 + 3.072;
    case 3: return 0.755 + 3.072;
    default: return 0.286 + 3.000;
  }
}

Sentence to_sentence(const FdpTransmit& p) {
  return Sentence{"CC", "TDP",
                  {std::to_string(p.destination), std::to_string(p.rate), p.ack ? "1" : "0", "0", hex_encode(p.data)}};
}

Result<FdpTransmit> parse_fdp_transmit(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCTDP"});
  reader.require(5);
  FdpTransmit p;
  p.destination = static_cast<int>(reader.integer(1, "dest", 0, kMaxAddress));
  p.rate = static_cast<int>(reader.integer(2, "rate", 1, 5));
  p.ack = reader.flag(3, "ack");
  reader.integer(4, "reserved", 0, 0);
  p.data = reader.hex(5, "data");
  if (reader.ok() && fdp_max_data_bytes(p.rate) == 0) {
    reader.fail(ErrorKind::kBadField, "$CCTDP field 2 (rate) '" + reader.text(2) + "' is not an FDP rate (1, 3, 5)");
  }
  if (reader.ok() && static_cast<int>(p.data.size()) > kFdpMiniFrameBytes + fdp_max_data_bytes(p.rate)) {
    reader.fail(ErrorKind::kBadField, "$CCTDP field 5 (data) has " + std::to_string(p.data.size()) +
                                          " bytes, more than rate " + reader.text(2) + " carries");
  }
  return reader.finish(p);
}

Sentence to_sentence(const FdpEcho& echo, int mini_frames, int data_frames) {
  return Sentence{"CA", "TDP",
                  {echo.error ? "1" : "0", echo.id, std::to_string(echo.destination), std::to_string(echo.rate), "0",
                   "0", std::to_string(mini_frames), std::to_string(data_frames)}};
}

Result<FdpEcho> parse_fdp_echo(const Sentence& sentence) {
  FieldReader reader(sentence, {"CATDP"});
  reader.require(4);
  FdpEcho echo;
  echo.error = reader.integer(1, "err flag", -1000000, 1000000) != 0;
  echo.id = reader.text(2);
  echo.destination = static_cast<int>(reader.integer(3, "dest", 0, kMaxAddress));
  echo.rate = static_cast<int>(reader.integer(4, "rate", 0, 6));
  return reader.finish(echo);
}

bool FdpReceived::intact() const {
  for (const auto* frames : {&mini_frames, &data_frames}) {
    for (const FdpFrame& frame : *frames) {
      if (!frame.crc_ok) return false;
    }
  }
  return true;
}

std::string FdpReceived::payload() const {
  std::string bytes;
  for (const auto* frames : {&mini_frames, &data_frames}) {
    for (const FdpFrame& frame : *frames) bytes += frame.data;
  }
  return bytes;
}

Sentence to_sentence(const FdpReceived& p) {
  return Sentence{"CA", "RDP",
                  {std::to_string(p.source), std::to_string(p.destination), std::to_string(p.rate), p.ack ? "1" : "0",
                   "0", frame_list(p.mini_frames), frame_list(p.data_frames)}};
}

Result<FdpReceived> parse_fdp_received(const Sentence& sentence) {
  FieldReader reader(sentence, {"CARDP"});
  reader.require(7);
  FdpReceived p;
  p.source = static_cast<int>(reader.integer(1, "src", 0, kMaxAddress));
  p.destination = static_cast<int>(reader.integer(2, "dest", 0, kMaxAddress));
  p.rate = static_cast<int>(reader.integer(3, "rate", 0, 6));
  p.ack = reader.flag(4, "ack");
  if (!reader.ok()) return reader.finish(p);
  auto mini = parse_frame_list(sentence.field(6), "$CARDP field 6 (mini-frames)");
  if (!mini) return mini.error();
  auto data = parse_frame_list(sentence.field(7), "$CARDP field 7 (data-frames)");
  if (!data) return data.error();
  p.mini_frames = std::move(*mini);
  p.data_frames = std::move(*data);
  return p;
}

}  // namespace acomms::micromodem
