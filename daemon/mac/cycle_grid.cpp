#include "mac/cycle_grid.h"

#include <cmath>

namespace acomms::mac {
namespace {

constexpr Nanoseconds kDay = std::chrono::hours(24);

// Floor division: times before the reference must land in negative cycles,
// not be rounded towards zero.
int64_t floor_div(int64_t a, int64_t b) {
  int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

Nanoseconds since_unix_epoch(CycleGrid::time_point t) {
  return std::chrono::duration_cast<Nanoseconds>(t.time_since_epoch());
}

CycleGrid::time_point at(Nanoseconds since_epoch) {
  return CycleGrid::time_point(
      std::chrono::duration_cast<CycleGrid::time_point::duration>(since_epoch));
}

}  // namespace

Nanoseconds to_nanoseconds(double seconds) {
  // Whole and fractional parts apart: an epoch (~1.7e9 s) times 1e9 is
  // beyond a double's exact integers, and would be off by up to 128 ns.
  const double whole = std::floor(seconds);
  return Nanoseconds(static_cast<int64_t>(whole) * 1'000'000'000 +
                     std::llround((seconds - whole) * 1e9));
}

CycleGrid::CycleGrid(std::optional<double> epoch, Nanoseconds cycle_length)
    : length_(cycle_length) {
  if (epoch) epoch_ = to_nanoseconds(*epoch);
}

CycleGrid::CycleStart CycleGrid::next(time_point t) const {
  const int64_t now = since_unix_epoch(t).count();
  const int64_t length = length_.count();
  if (epoch_) {
    int64_t k = ceil_div(now - epoch_->count(), length);
    return {at(*epoch_ + k * length_), k};
  }
  const int64_t day = kDay.count();
  const int64_t midnight = floor_div(now, day) * day;
  // Cycles that fit in a day; a cycle longer than a day still gets one.
  const int64_t per_day = std::max<int64_t>(1, day / length);
  int64_t k = ceil_div(now - midnight, length);
  if (k < per_day) return {at(Nanoseconds(midnight + k * length)), k};
  return {at(Nanoseconds(midnight + day)), 0};
}

std::optional<CycleGrid::CycleStart> CycleGrid::containing(time_point t) const {
  const int64_t now = since_unix_epoch(t).count();
  const int64_t length = length_.count();
  if (epoch_) {
    int64_t k = floor_div(now - epoch_->count(), length);
    return CycleStart{at(*epoch_ + k * length_), k};
  }
  const int64_t day = kDay.count();
  const int64_t midnight = floor_div(now, day) * day;
  const int64_t per_day = std::max<int64_t>(1, day / length);
  int64_t k = (now - midnight) / length;
  if (k >= per_day) return std::nullopt;
  return CycleStart{at(Nanoseconds(midnight + k * length)), k};
}

}  // namespace acomms::mac
