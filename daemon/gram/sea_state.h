// Sea state → wind speed, for the noise model's wind term (spec §6.6).
//
// Problem: users know the sea state ("sea state 2"), the Wenz/Coates model
// wants a wind speed. Decision: the spec's correspondence, reading sea state
// N as Beaufort force N (2 → 2.5 m/s, 3 → 4.5 m/s, 4 → 7 m/s), completed
// with the middle of the Beaufort bands for the other forces: 0 → 0,
// 1 → 1, 5 → 9.5, 6 → 12 m/s. Sea states above 6 are refused: nobody runs
// an acoustic link trial in a gale, and the model's wind term was not
// fitted there. Thread-safe: pure functions.
#pragma once

#include <optional>

namespace acomms::gram {

inline constexpr int kMaxSeaState = 6;

// nullopt outside 0..kMaxSeaState.
std::optional<double> wind_speed_for_sea_state(int sea_state);

}  // namespace acomms::gram
