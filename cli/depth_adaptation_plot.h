#pragma once
// A picture of the depth-adaptation experiment, for `acommsctl sim
// depth-adaptation --png` (the thesis's Fig. 4.7d): receipt probability
// (0 to 1, grid every 0.1) against range (km, the bins' centres), one line
// per strategy: the fixed depths from red (the shallowest) to blue (the
// deepest), the adaptive strategy thick and black; a legend names each and,
// below it, the source (the buoy at its depth, range 0) and the receiver
// (the vehicle, at each strategy's depth); a title names the input.

#include <string>
#include <vector>

#include "eval/depth_adaptation.h"
#include "eval/depth_adaptation_sweep.h"
#include "plot/canvas.h"

namespace acomms::cli {

// Writes `path` as PNG; throws std::runtime_error if it cannot be written.
// `input` names the environment in the title.
void write_depth_adaptation_png(const std::string& path, const eval::DepthAdaptationResult& result,
                                const std::string& input, double buoy_depth_m);
// The picture itself, for tests; and the colour of strategy `s`.
plot::Canvas draw_depth_adaptation(const eval::DepthAdaptationResult& result, const std::string& input,
                                   double buoy_depth_m);
// Where the source and receiver note is (the top of its first line).
int nodes_note_y(std::size_t legend_rows);
plot::Rgb strategy_colour(const eval::DepthAdaptationResult& result, std::size_t s);
// Where the legend's sample line of strategy `s` is (its middle).
int legend_x();
int legend_y(std::size_t s);
// The sweep (`--sweep`): packets received against the swept value, the
// adaptive strategy black and the best fixed depth red, each value's ±1
// standard error a vertical bar; `input` names the environment.
void write_depth_adaptation_sweep_png(const std::string& path, eval::SweepQuantity quantity,
                                      const std::vector<eval::SweepPoint>& points, const std::string& input,
                                      double buoy_depth_m);
plot::Canvas draw_depth_adaptation_sweep(eval::SweepQuantity quantity, const std::vector<eval::SweepPoint>& points,
                                         const std::string& input, double buoy_depth_m);

}  // namespace acomms::cli
