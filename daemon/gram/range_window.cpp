// Range window: shared/spec/gram.md §6.1.
#include "gram/range_window.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "gram/validation_text.h"

namespace acomms::gram {
namespace {

std::optional<std::string> check_motion(double speed_mps, double heading_deg, double horizon_s) {
  if (auto e = require_at_least("speed_mps", speed_mps, 0.0)) return e;
  if (!std::isfinite(heading_deg))
    return "heading_deg = " + format_number(heading_deg) + " must be a finite number of degrees";
  return require_greater("horizon_s", horizon_s, 0.0);
}

}  // namespace

double range_window_length(double speed_mps, double heading_deg, double horizon_s) {
  if (auto e = check_motion(speed_mps, heading_deg, horizon_s)) throw std::invalid_argument(*e);
  return speed_mps * std::cos(heading_deg * std::numbers::pi / 180.0) * horizon_s;
}

std::optional<std::string> validate_range_window_input(const RangeWindowInput& in) {
  if (auto e = require_at_least("range_m", in.range_m, 0.0)) return e;
  if (auto e = check_motion(in.speed_mps, in.heading_deg, in.horizon_s)) return e;
  return require_greater("range_step_m", in.range_step_m, 0.0);
}

RangeWindow range_window(const RangeWindowInput& in) {
  if (auto e = validate_range_window_input(in)) throw std::invalid_argument(*e);
  RangeWindow w;
  w.delta_r_m = range_window_length(in.speed_mps, in.heading_deg, in.horizon_s);
  w.closing = w.delta_r_m < 0;
  double length = std::abs(w.delta_r_m);
  if (length < in.range_step_m) {
    length = in.range_step_m;
    w.widened = true;
  }
  if (w.closing) {
    w.begin_m = std::max(in.range_m - length, 0.0);
    w.end_m = in.range_m;
    // Closing from r₀ = 0 leaves nothing behind: look at the first spacing.
    if (!(w.end_m > w.begin_m)) w.end_m = w.begin_m + in.range_step_m;
  } else {
    w.begin_m = in.range_m;
    w.end_m = in.range_m + length;
  }
  return w;
}

}  // namespace acomms::gram
