#include "link/backoff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace acomms::link {

Backoff::duration seconds_to_duration(double seconds) {
  return Backoff::duration(static_cast<Backoff::duration::rep>(std::llround(seconds * 1e9)));
}

double duration_to_seconds(Backoff::duration d) { return static_cast<double>(d.count()) / 1e9; }

std::string format_seconds(Backoff::duration d) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", duration_to_seconds(d));
  return text;
}

Backoff::Backoff(double min_s, double max_s)
    : min_(seconds_to_duration(min_s > 0 ? min_s : 1.0)),
      max_(std::max(min_, seconds_to_duration(max_s))),
      current_(min_) {}

Backoff::duration Backoff::next() {
  duration now = current_;
  current_ = std::min(max_, current_ * 2);
  return now;
}

}  // namespace acomms::link
