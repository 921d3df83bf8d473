// The range window of the depth objective (Schneider (2013) eq. 4.1, spec
// §6.1).
//
// Problem: the depth a vehicle should hold depends on the ranges it will
// cross before the model is asked again, not on its range now. Decision:
// the window is the stretch the vehicle covers along the line to the other
// node in the model horizon τ_a: Δr = |v₀| cos Θ τ_a.
//
// Heading convention: Θ is the angle between the vehicle's heading and the
// line pointing AWAY from the other node (Θ = 0: opening straight away,
// Θ = 180°: closing straight in). Only cos Θ matters, so port and starboard
// (±Θ) give the same window; Θ is in degrees, any finite value.
//   - cos Θ ≥ 0 (opening, or exactly abeam): [r₀, r₀ + Δr).
//   - cos Θ < 0 (closing): [r₀ − |Δr|, r₀); the start is clipped at range 0.
//   - |Δr| smaller than the receiver range spacing: widened to one spacing
//     in the same direction, so the window always holds at least one grid
//     range (a vehicle at rest, or abeam, still gets an answer for r₀).
// Invariants: begin_m < end_m, begin_m ≥ 0. Thread-safe: pure functions.
#pragma once

#include <optional>
#include <string>

namespace acomms::gram {

struct RangeWindowInput {
  double range_m = 0;       // r₀, the current range to the other node, ≥ 0
  double speed_mps = 0;     // |v₀|, ≥ 0
  double heading_deg = 0;   // Θ, relative to the line away from the other node
  double horizon_s = 120;   // τ_a, > 0 (GLINT10: 120 s)
  double range_step_m = 0;  // the receiver grid's range spacing, > 0
};

struct RangeWindow {
  double delta_r_m = 0;  // eq. 4.1 as signed: |v₀| cos Θ τ_a (negative when closing)
  double begin_m = 0;    // the window [begin_m, end_m)
  double end_m = 0;
  bool closing = false;  // cos Θ < 0
  bool widened = false;  // |Δr| was below range_step_m
};

// Eq. 4.1 exactly (signed). Throws std::invalid_argument on a bad argument.
double range_window_length(double speed_mps, double heading_deg, double horizon_s);

// nullopt when `in` is usable, else a message naming the field and bound.
std::optional<std::string> validate_range_window_input(const RangeWindowInput& in);

// Throws std::invalid_argument with validate_range_window_input's message.
RangeWindow range_window(const RangeWindowInput& in);

}  // namespace acomms::gram
