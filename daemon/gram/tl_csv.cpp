// The TL field as CSV text (see tl_csv.h).
#include "gram/tl_csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <thread>

namespace acomms::gram {
namespace {

// Below this many rows one thread formats faster than two start.
constexpr std::size_t kRowsWorthAThread = 20'000;
// The row's TL and newline, at most; the coordinates' text is copied apart.
constexpr std::size_t kMaxTlChars = 320 + 1;

// Fixed notation (a CSV reader wants 100000, not 1e+05), with the fewest
// digits that read back as `value`.
std::string shortest(double value) {
  char text[400];
  const auto end = std::to_chars(text, text + sizeof text, value, std::chars_format::fixed).ptr;
  return std::string(text, end);
}

// The coordinates' text, formatted once: a rectilinear grid repeats every
// range on each depth's rows.
struct Coordinates {
  std::vector<std::string> range, depth;
  std::size_t longest_range = 0, longest_depth = 0;
  explicit Coordinates(const TransmissionLoss& tl) {
    range.reserve(tl.range_m.size());
    for (double r : tl.range_m) {
      range.push_back(shortest(r) + ",");
      longest_range = std::max(longest_range, range.back().size());
    }
    depth.reserve(tl.depth_m.size());
    for (double z : tl.depth_m) {
      depth.push_back(shortest(z) + ",");
      longest_depth = std::max(longest_depth, depth.back().size());
    }
  }
};

char* put_tl(char* out, double tl_db) {
  if (std::isnan(tl_db)) return out;  // no value on the source axis
  if (std::isinf(tl_db)) {
    std::memcpy(out, tl_db > 0 ? "inf" : "-inf", tl_db > 0 ? 3 : 4);
    return out + (tl_db > 0 ? 3 : 4);
  }
  return put_fixed3(out, tl_db);
}

char* put_text(char* out, const std::string& text) {
  std::memcpy(out, text.data(), text.size());
  return out + text.size();
}

// Rows [first, last) into `text`. Written through a pointer into space
// made ahead (a row's longest text), not appended piece by piece, and the
// row's range and depth counted rather than divided out of i: this loop
// is the CSV's whole cost.
void format_rows(const TransmissionLoss& tl, const Coordinates& text_of, std::size_t first, std::size_t last,
                 std::string& text) {
  if (first == last) return;  // (an empty field has no range to divide by)
  const std::size_t longest_row = text_of.longest_range + text_of.longest_depth + kMaxTlChars;
  std::size_t used = text.size();
  text.resize(used + (last - first) * 28 + longest_row);
  const std::size_t nr = tl.range_m.size();
  std::size_t ir = tl.irregular ? first : first % nr, iz = tl.irregular ? first : first / nr;
  for (std::size_t i = first; i < last; ++i) {
    if (text.size() - used < longest_row) text.resize(2 * text.size());
    char* out = text.data() + used;
    out = put_text(out, text_of.range[ir]);
    out = put_text(out, text_of.depth[iz]);
    out = put_tl(out, tl.tl_db[i]);
    *out++ = '\n';
    used = static_cast<std::size_t>(out - text.data());
    if (tl.irregular) {
      ++ir;
      ++iz;
    } else if (++ir == nr) {
      ir = 0;
      ++iz;
    }
  }
  text.resize(used);
}

}  // namespace

char* put_fixed3(char* out, double value) {
  // Fast path: v·1000 rounded to an integer. The product is within 2^-13 of
  // the exact one when |v·1000| < 2^40, so wherever its fraction is not
  // within 0.001 of one half, both round to the same integer; near a half
  // (and for huge values) std::to_chars decides exactly.
  const double scaled = value * 1000.0;
  if (std::abs(scaled) < 0x1p40) {
    const double nearest = std::nearbyint(scaled);
    if (std::abs(scaled - nearest) < 0.499) {
      if (std::signbit(value)) *out++ = '-';  // printf writes "-0.000" too
      const auto units = static_cast<unsigned long long>(std::abs(nearest));
      out = std::to_chars(out, out + 24, units / 1000).ptr;
      const unsigned thousandths = static_cast<unsigned>(units % 1000);
      out[0] = '.';
      out[1] = static_cast<char>('0' + thousandths / 100);
      out[2] = static_cast<char>('0' + thousandths / 10 % 10);
      out[3] = static_cast<char>('0' + thousandths % 10);
      return out + 4;
    }
  }
  return std::to_chars(out, out + 320, value, std::chars_format::fixed, 3).ptr;
}

std::vector<std::string> tl_csv_blocks(const TransmissionLoss& tl, unsigned threads) {
  const std::size_t rows = tl.tl_db.size();
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t blocks =
      std::clamp<std::size_t>(std::min<std::size_t>(threads, rows / kRowsWorthAThread), 1, threads);
  const Coordinates text_of(tl);
  std::vector<std::string> out(blocks);
  out[0] = "range_m,depth_m,tl_db\n";
  auto format_block = [&](std::size_t b) {
    format_rows(tl, text_of, rows * b / blocks, rows * (b + 1) / blocks, out[b]);
  };
  // jthread: if a helper cannot be started, the ones already running are
  // joined as the error leaves, instead of std::terminate.
  std::vector<std::jthread> helpers;
  for (std::size_t b = 1; b < blocks; ++b) helpers.emplace_back(format_block, b);
  format_block(0);
  for (auto& t : helpers) t.join();
  return out;
}

}  // namespace acomms::gram
