// libFuzzer target: a Micro-Modem byte stream (power-up noise, binary
// bursts, cut sentences, a gateway's arbitrary chunks) through LineFramer.
// The first two bytes choose the line bound and the chunk size. Whatever
// the stream, the framer's buffer stays within the bound, every line it
// yields is one '$'-started line without line ends, and cutting the stream
// into chunks changes nothing.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "micromodem/nmea/line_framer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace acomms::micromodem;
  if (size < 2) return 0;
  // Small bounds reach the over-long path without megabyte inputs.
  size_t max_line = 1 + data[0] % 64 * 4;
  if (data[0] == 255) max_line = kMaxLineLength;
  size_t chunk = 1 + data[1] % 32;
  std::string_view stream(reinterpret_cast<const char*>(data) + 2, size - 2);

  LineFramer whole(max_line);
  std::vector<std::string> expected = whole.push(stream);
  if (whole.buffered() > max_line) __builtin_trap();

  LineFramer chunked(max_line);
  std::vector<std::string> lines;
  for (size_t at = 0; at < stream.size(); at += chunk) {
    for (std::string& line : chunked.push(stream.substr(at, chunk))) lines.push_back(std::move(line));
    if (chunked.buffered() > max_line) __builtin_trap();
  }
  if (lines != expected) __builtin_trap();
  const LineFramer::Counters& a = whole.counters();
  const LineFramer::Counters& b = chunked.counters();
  if (a.lines != b.lines || a.noise_bytes != b.noise_bytes || a.truncated_lines != b.truncated_lines ||
      a.overlong_lines != b.overlong_lines || a.lines != expected.size()) {
    __builtin_trap();
  }
  for (const std::string& line : lines) {
    if (line.empty() || line.front() != '$' || line.size() > max_line) __builtin_trap();
    if (line.find_first_of("\r\n") != std::string::npos) __builtin_trap();
    if (line.find('$', 1) != std::string::npos) __builtin_trap();
    // What the driver does next: must not crash whatever the line holds.
    Result<Sentence> sentence = parse_sentence(line);
    if (!sentence && sentence.error().text.empty()) __builtin_trap();
  }
  return 0;
}
