// Validation of an Environment before a run.
//
// Problem: a model fed at sea with a bad profile must say what is wrong in
// words the operator can act on, not produce NaNs or crash. Decision: one
// pass over every field; the first failure is returned as a message that
// names the field and the bound (e.g. "sound_speed[3].depth_m = 40 must be
// greater than sound_speed[2].depth_m = 50"). Thread-safe: pure function.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "acomms/gram/environment.pb.h"

namespace acomms::gram {

struct ValidationLimits {
  std::size_t max_receivers = 4'000'000;  // grid points (depths × ranges)
  std::size_t max_beams = 100'000;
};

// nullopt when the environment can be run.
std::optional<std::string> validate_environment(const Environment& env,
                                                const ValidationLimits& limits = {});

// The depth of the bottom at the deepest point (last SSP depth if flat).
double deepest_bottom(const Environment& env);

}  // namespace acomms::gram
