#pragma once
// A picture of a transmission-loss field, for `acommsctl gram tl --png`:
// TL against range (across) and depth (down) in a colour scale from the
// field's lowest TL (dark red) to 60 dB more (dark blue); receivers with no
// value or in shadow are light grey. To the right, the sound speed profile
// on the same depth axis. No text: the numbers are in the CSV output.

#include <string>

#include "acomms/gram/depth_objective.pb.h"
#include "acomms/gram/environment.pb.h"
#include "gram/transmission_loss.h"

namespace acomms::cli {

// Writes `path` as PNG; throws std::runtime_error if it cannot be written.
void write_tl_png(const std::string& path, const gram::TransmissionLoss& tl,
                  const gram::Environment& env);

// The depth objective, for `acommsctl gram depth --png`: depth down, the
// objective across [0, 1]; raw in grey, filtered in black, the best depth
// as a red line, depths below the window's shallowest bottom shaded. No text.
void write_objective_png(const std::string& path, const gram::DepthObjectiveReply& reply);

}  // namespace acomms::cli
