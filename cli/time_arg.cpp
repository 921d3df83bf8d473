#include "time_arg.h"

#include <charconv>

#include "rpc_error.h"

namespace acomms::cli {

double parse_time(const std::string& text, double now_s) {
  if (text == "now") return now_s;
  auto bad = [&] {
    return UsageError("time \"" + text + "\": give seconds since the Unix epoch, \"now\", or -30s, -10m, -2h, -1d");
  };
  if (text.size() >= 3 && text[0] == '-') {
    double unit = 0;
    switch (text.back()) {
      case 's': unit = 1; break;
      case 'm': unit = 60; break;
      case 'h': unit = 3600; break;
      case 'd': unit = 86400; break;
      default: throw bad();
    }
    double amount = 0;
    const char* end = text.data() + text.size() - 1;
    auto [ptr, error] = std::from_chars(text.data() + 1, end, amount);
    if (error != std::errc() || ptr != end || amount < 0) throw bad();
    return now_s - amount * unit;
  }
  double seconds = 0;
  const char* end = text.data() + text.size();
  auto [ptr, error] = std::from_chars(text.data(), end, seconds);
  if (text.empty() || error != std::errc() || ptr != end || seconds < 0) throw bad();
  return seconds;
}

}  // namespace acomms::cli
