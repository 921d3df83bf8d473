// libFuzzer target: .bty bathymetry import of untrusted text. Import must
// return points with strictly increasing ranges or throw ImportError.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "gram/bellhop_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const auto points = acomms::gram::import_bellhop_bty(
        std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.bty");
    for (std::size_t i = 1; i < points.size(); ++i)
      if (!(points[i].range_m() > points[i - 1].range_m())) std::abort();
  } catch (const acomms::gram::ImportError&) {
  }
  return 0;
}
