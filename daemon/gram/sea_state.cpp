#include "gram/sea_state.h"

#include <array>

namespace acomms::gram {

std::optional<double> wind_speed_for_sea_state(int sea_state) {
  static constexpr std::array<double, kMaxSeaState + 1> kWindMps = {0.0, 1.0, 2.5, 4.5, 7.0, 9.5, 12.0};
  if (sea_state < 0 || sea_state > kMaxSeaState) return std::nullopt;
  return kWindMps[static_cast<std::size_t>(sea_state)];
}

}  // namespace acomms::gram
