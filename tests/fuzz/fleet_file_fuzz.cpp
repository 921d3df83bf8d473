// libFuzzer target: fleet files (core/fleet.h), which an operator writes by
// hand and `acommsd --fleet` and `acommsctl fleet` read. Parsing and
// resolving every node must end in a config or a ConfigError that says
// why, never a crash, a hang (parent cycles) or another exception.

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/config_error.h"
#include "core/fleet.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace acomms::core;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // A path in a directory with no files: an include names nothing real.
    const Fleet fleet = Fleet::parse(text, "/nonexistent/fleet.conf");
    for (const std::string& name : fleet.node_names()) {
      try {
        (void)node_config(fleet, name);
      } catch (const ConfigError& e) {
        if (std::string(e.what()).empty()) __builtin_trap();  // every refusal says why
      }
    }
  } catch (const ConfigError& e) {
    if (std::string(e.what()).empty()) __builtin_trap();
  }
  return 0;
}
