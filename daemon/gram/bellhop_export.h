// An Environment written as BELLHOP input (.env and, with bathymetry, the
// .bty beside it), for the external engine (spec §7.2, §7.3).
//
// Problem: users who run BELLHOP itself must get the run they asked for,
// options included. Decision: write exactly what the importer
// (bellhop_import.h) reads back into the same Environment: attenuation in
// Np/m (TOPOPT(3) 'N'), ranges in km, one source, geometric beams ('G' hat,
// 'B' Gaussian), point source, rectilinear or irregular receivers. Numbers
// with 17 significant digits, so the round trip is exact. Thread-safe.
#pragma once

#include <optional>
#include <string>

#include "acomms/gram/environment.pb.h"

namespace acomms::gram {

struct BellhopInput {
  std::string env;                // the .env text
  std::optional<std::string> bty; // the .bty text, when the bottom is not flat
};

// `env` must be valid (validate_environment). TL runs only: RUNTYPE(1) is
// the field mode, never arrivals.
BellhopInput export_bellhop(const Environment& env);

}  // namespace acomms::gram
