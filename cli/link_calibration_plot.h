#pragma once
// The picture of acommsctl link calibrate --png: on the left each decoded
// packet's measured SNR against the model's predicted SNR (the 1:1 line
// grey, each link's fitted offset dashed in its colour); on the right the
// fraction decoded per 1 dB of predicted SNR (dots) and each rate's fitted
// reception curve. One colour per link and rate, named in the legend, so a
// reader sees how far the site departs from the model, and how sharp the
// modem's threshold is, without the text output.
//
// Thread-safety: pure functions.
#include <string>
#include <vector>

#include "eval/link_calibration.h"
#include "plot/canvas.h"

namespace acomms::cli {

plot::Canvas draw_link_calibration(const std::vector<eval::PacketSample>& samples,
                                   const std::vector<eval::LinkCalibration>& links);

// Throws std::runtime_error naming `path` when it cannot be written.
void write_link_calibration_png(const std::string& path, const std::vector<eval::PacketSample>& samples,
                                const std::vector<eval::LinkCalibration>& links);

}  // namespace acomms::cli
