// libFuzzer target: CTD cast CSV of untrusted text, and the profile made
// from it. Reading must return samples or throw ImportError; the profile's
// depths must strictly increase and its speeds be finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "gram/ctd_cast.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const auto cast = acomms::gram::read_ctd_csv(
        std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.csv");
    const auto profile = acomms::gram::sound_speed_from_ctd(cast);
    for (std::size_t i = 0; i < profile.size(); ++i) {
      if (!std::isfinite(profile[i].speed_mps())) std::abort();
      if (i > 0 && !(profile[i].depth_m() > profile[i - 1].depth_m())) std::abort();
    }
  } catch (const acomms::gram::ImportError&) {
  }
  return 0;
}
