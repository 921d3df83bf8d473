// libFuzzer target: an Iridium modem's serial byte stream (echo, unsolicited
// lines, binary MT blocks, garbage, a gateway's arbitrary chunks) through
// the AT reader and its line classification. The first two bytes choose the
// chunk size and where the reader is told to expect a block. Whatever the
// stream: the reader's buffer stays bounded, cutting the stream into chunks
// changes nothing, every line is printable and without line ends, and every
// block's payload is within the MT limit with a truthful checksum flag.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "iridium/at/at_reader.h"
#include "iridium/at/sbd_binary.h"

namespace {

using acomms::iridium::AtEvent;
using acomms::iridium::AtReader;

// A comparable digest of the events.
std::string digest(const std::vector<AtEvent>& events) {
  std::string out;
  for (const AtEvent& e : events) {
    out += std::to_string(static_cast<int>(e.kind)) + ":";
    if (e.kind == AtEvent::Kind::kLine) out += std::to_string(static_cast<int>(e.line.kind)) + e.line.text;
    if (e.kind == AtEvent::Kind::kBlock) out += e.block.payload + (e.block.checksum_ok ? "+" : "-");
    if (e.kind == AtEvent::Kind::kBadBlock) out += std::to_string(e.bad_length);
    out += "\n";
  }
  return out;
}

void check(const std::vector<AtEvent>& events) {
  for (const AtEvent& e : events) {
    if (e.kind == AtEvent::Kind::kLine) {
      const std::string& text = e.line.text;
      if (text.empty() || text.size() > acomms::iridium::kMaxLineBytes) __builtin_trap();
      for (char c : text) {
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) __builtin_trap();
      }
    } else if (e.kind == AtEvent::Kind::kBlock) {
      if (e.block.payload.size() > acomms::iridium::kMaxMtBytes) __builtin_trap();
      if (e.block.checksum_ok != (e.block.checksum == acomms::iridium::sbd_checksum(e.block.payload))) __builtin_trap();
    }
  }
}

// Feeds `stream` in chunks, switching to block mode at `binary_at`.
std::vector<AtEvent> run(std::string_view stream, size_t chunk, size_t binary_at) {
  AtReader reader;
  std::vector<AtEvent> out;
  size_t at = 0;
  while (at < stream.size()) {
    size_t end = std::min(stream.size(), at + chunk);
    if (at < binary_at && binary_at < end) end = binary_at;  // the switch lands between the same two bytes
    if (at == binary_at) reader.expect_binary();
    for (AtEvent& e : reader.push(stream.substr(at, end - at))) out.push_back(std::move(e));
    if (reader.buffered() > acomms::iridium::kMaxLineBytes + acomms::iridium::kMaxMtBytes + 4) __builtin_trap();
    at = end;
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const size_t chunk = 1 + data[0] % 32;
  std::string_view stream(reinterpret_cast<const char*>(data) + 2, size - 2);
  const size_t binary_at = stream.empty() ? 0 : data[1] % (stream.size() + 1);
  std::vector<AtEvent> whole = run(stream, stream.size() + 1, binary_at);
  std::vector<AtEvent> chunked = run(stream, chunk, binary_at);
  check(whole);
  if (digest(whole) != digest(chunked)) __builtin_trap();
  return 0;
}
