// libFuzzer target: BELLHOP .env import of untrusted text (users bring these
// files; the daemon may be fed them at sea). Import must return an
// environment or throw ImportError; validation of whatever imports must
// return a message or nothing. Any other exception, crash or sanitizer
// report is a bug. The bytes after the first NUL, if any, are the .bty.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "gram/bellhop_import.h"
#include "gram/environment_validation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const std::string_view env = input.substr(0, nul);
  const std::string bty(nul == std::string_view::npos ? std::string_view() : input.substr(nul + 1));
  const acomms::gram::SideFileLoader side = [&](const std::string& ext) -> std::optional<std::string> {
    if (ext == "bty" && nul != std::string_view::npos) return bty;
    return std::nullopt;
  };
  try {
    const auto imported = acomms::gram::import_bellhop_env(env, "fuzz.env", side);
    (void)acomms::gram::validate_environment(imported.environment);
  } catch (const acomms::gram::ImportError&) {
  }
  return 0;
}
