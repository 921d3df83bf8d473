// libFuzzer target: a .shd field from an external engine (untrusted bytes).
// Reading must return a field or throw ShdError; a field read must have as
// many pressure values as its header's counts say, and writing it back in
// its own layout and reading again must give the same values.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "gram/shd_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace acomms::gram;
  try {
    const ShdField field = read_shd(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.shd");
    const std::size_t records = static_cast<std::size_t>(field.n_freq) * field.n_theta *
                                field.source_depth_m.size() * field.receiver_depth_m.size();
    if (field.pressure.size() != records * field.receiver_range_m.size()) std::abort();
    const ShdField again = read_shd(write_shd(field, field.layout), "again.shd");
    if (again.pressure.size() != field.pressure.size()) std::abort();
    if (!field.pressure.empty() &&
        std::memcmp(again.pressure.data(), field.pressure.data(), field.pressure.size() * sizeof(field.pressure[0])) != 0)
      std::abort();
  } catch (const ShdError&) {
  }
  return 0;
}
