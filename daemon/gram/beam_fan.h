// The launch fan: how many beams, at which angles.
//
// Problem: too few beams leave the field under-sampled at range; BELLHOP's
// automatic count is the reference users compare with. Decision (spec
// §4.7): N = max(300, 0.3 R_max f / c(z_s), 10π R_max / D) over the whole
// fan, R_max the farthest receiver and D the water depth; an explicit count
// in the environment is used as given, never reduced.
// Thread-safe: pure functions.
#pragma once

#include <cstdint>

#include "acomms/gram/environment.pb.h"

namespace acomms::gram {

std::uint32_t automatic_beam_count(const Environment& env);
// The count a run uses: the environment's, or the automatic one if 0.
std::uint32_t beam_count(const Environment& env);

}  // namespace acomms::gram
