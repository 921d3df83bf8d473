// Import of BELLHOP-format environment (.env) and bathymetry (.bty) files.
//
// Problem: users bring environments they already trust in BELLHOP's format;
// a model that silently misreads an option gives confident wrong answers.
// Decision: the 2-D options of spec §7.4 are converted into an Environment
// (SI units: km → m, attenuation → Np/m); every other option is refused with
// an ImportError naming the file, the line, the option and why.
// Side files (<root>.bty) come through a loader so the importer itself
// touches no file system (and can be fuzzed). Thread-safe: pure functions.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "gram/list_directed.h"

namespace acomms::gram {

struct ImportedEnvironment {
  Environment environment;
  std::vector<std::string> warnings;  // options accepted with a caveat
};

// Returns the text of <root>.<extension> (e.g. "bty"), or nullopt if absent.
using SideFileLoader = std::function<std::optional<std::string>(const std::string& extension)>;

ImportedEnvironment import_bellhop_env(std::string_view text, const std::string& file_name,
                                       const SideFileLoader& side_files);
// Reads `path` and its side files next to it (<root>.bty).
ImportedEnvironment import_bellhop_env_file(const std::filesystem::path& path);

// A .bty file: 'L' (piecewise linear, short format) only; ranges in km.
std::vector<BathymetryPoint> import_bellhop_bty(std::string_view text, const std::string& file_name);

// §1.3: attenuation `value` in BELLHOP unit `unit` (N F M W Q L) → Np/m.
double attenuation_np_per_m(char unit, double value, double speed_mps, double frequency_hz);

}  // namespace acomms::gram
