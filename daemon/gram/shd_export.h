// The model's field as BELLHOP's .shd (spec §7.5), for the plotting tools
// users already have.
//
// Problem: BELLHOP-based tools read a complex pressure field with its
// header (frequency, source and receiver positions), in BELLHOP's own sign
// convention, not TL in text. Decision: the 2023+ layout (float64 ranges in
// metres; depths float32 as the format stores them), one frequency, one
// bearing, one source at (0, 0); pressure written as −conj(p) of ours
// (spec §0: the phase BELLHOP's files carry, same magnitude); incoherent and
// semi-coherent runs have no phase and write √intensity, real and positive
// (a reader's TL = −20 log10 |p|, spec §7.5, is the run's). Where the model has no value (range 0) the pressure is 0 (TL
// infinite to a reader). Rectilinear grids only: the spec states no
// layout for irregular receivers, so such a field is refused rather than
// written in a layout a reader may take differently.
// Thread-safe: pure functions.
#pragma once

#include <stdexcept>
#include <string>

#include "acomms/gram/environment.pb.h"
#include "gram/shd_file.h"
#include "gram/transmission_loss.h"

namespace acomms::gram {

// `tl` from compute_transmission_loss(env, {.keep_pressure = true}) on the
// same `env`. Throws std::invalid_argument if `tl` has no pressure (naming
// keep_pressure) or its receivers are irregular.
ShdField shd_field_of(const TransmissionLoss& tl, const Environment& env);

}  // namespace acomms::gram
