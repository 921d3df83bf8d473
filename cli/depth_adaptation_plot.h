#pragma once
// A picture of the depth-adaptation experiment, for `acommsctl sim
// depth-adaptation --png` (the thesis's Fig. 4.7d): receipt probability (0
// at the bottom, 1 at the top, grid lines every 0.25) against range bin
// (across), one polyline per strategy: the fixed depths from red (the
// shallowest) to blue (the deepest), the adaptive strategy thick and black.
// No text: the numbers are in the table the command prints.

#include <string>

#include <vector>

#include "eval/depth_adaptation.h"
#include "eval/depth_adaptation_sweep.h"

namespace acomms::cli {

// Writes `path` as PNG; throws std::runtime_error if it cannot be written.
void write_depth_adaptation_png(const std::string& path, const eval::DepthAdaptationResult& result);
// The sweep (`--sweep`): receipt (0..1, grid every 0.25) against the swept
// value (across, FROM to TO), the adaptive strategy black and the best fixed
// depth red, each value's ±1 standard error as a vertical bar.
void write_depth_adaptation_sweep_png(const std::string& path, eval::SweepQuantity quantity,
                                      const std::vector<eval::SweepPoint>& points);

}  // namespace acomms::cli
