// The depth objective from range-averaged loss (Schneider (2013) eq. 4.3,
// spec §6.2).
//
// Problem: the vehicle needs a score in [0, 1] per depth, 1 for a lossless
// channel, 0 for a depth where messages are not expected to arrive.
// Decision: O(d) = max(1 − H̄(d)/H_max, 0). H_max is either fixed (GLINT10:
// 108 dB, under 1 % of messages received above it; 94 dB is the aggressive
// minimum-error threshold) or the window maximum max_d H̄(d), taken over the
// finite H̄ only (a shadow, H̄ = +inf, must not make every other depth score
// 1 − 0 = 1). A shadow depth scores 0. Thread-safe: pure functions.
#pragma once

#include <optional>
#include <span>
#include <vector>

namespace acomms::gram {

// The largest finite value; nullopt if none is finite.
std::optional<double> window_maximum(std::span<const double> h_bar_db);

// Eq. 4.3; throws std::invalid_argument unless h_max_db is finite and > 0.
std::vector<double> loss_objective(std::span<const double> h_bar_db, double h_max_db);

}  // namespace acomms::gram
