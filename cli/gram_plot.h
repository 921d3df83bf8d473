#pragma once
// A picture of a transmission-loss field, for `acommsctl gram tl --png`:
// TL against range (across, km) and depth (down, m) in a colour scale from
// the field's lowest TL (dark red) to 60 dB more (dark blue), with its
// colour bar in dB; receivers with no value or in shadow are light grey. To
// the right, the sound speed profile (m/s) on the same depth axis. A title
// names the input and the frequency; the source is a white-ringed dot at
// range 0 and its depth; a receiver (the map's vehicle, `gram tl
// --receiver`) is a white-ringed black square at its range and depth, with
// a dotted white line across the field at its depth and its label.

#include <optional>
#include <string>

#include "acomms/gram/depth_objective.pb.h"
#include "acomms/gram/environment.pb.h"
#include "gram/transmission_loss.h"
#include "plot/canvas.h"

namespace acomms::cli {

// One node to mark in the field: at `range_m` from the source, `depth_m`.
struct TlReceiver {
  double range_m = 0;
  double depth_m = 0;
  std::string label;  // e.g. "node 2, 15 m"
};
struct TlMarks {
  std::string source = "source";     // the source's label (the map: "buoy, node 3")
  std::optional<TlReceiver> receiver;
};

// Writes `path` as PNG; throws std::runtime_error if it cannot be written.
// `input` names the environment in the title (its file name).
void write_tl_png(const std::string& path, const gram::TransmissionLoss& tl, const gram::Environment& env,
                  const std::string& input, const TlMarks& marks = {});
// The picture itself, for tests and the map server.
plot::Canvas draw_tl(const gram::TransmissionLoss& tl, const gram::Environment& env, const std::string& input,
                     const TlMarks& marks = {});
// The pixel draw_tl puts (range_m, depth_m) of `tl` and `env` on (the
// centre of a mark there).
std::pair<int, int> tl_pixel(const gram::TransmissionLoss& tl, const gram::Environment& env, double range_m,
                             double depth_m);
inline constexpr plot::Rgb kTlReceiverMark{0, 0, 0};
// The colour of TL `db` when the field's lowest is `best_db`.
plot::Rgb tl_colour(double db, double best_db);
// Where draw_tl puts the colour bar (x of its middle, y of `db`).
int tl_colour_bar_x();
int tl_colour_bar_y(double db, double best_db);

// The depth objective, for `acommsctl gram depth --png`: depth down (m),
// the objective across [0, 1]; raw in grey, filtered in black, the
// receiver's best depth (where it is sent) as a red line, the source (the
// other node) at its depth as a dashed blue line when known, depths below
// the window's shallowest bottom shaded; a legend and a title (`title`:
// what was asked).
void write_objective_png(const std::string& path, const gram::DepthObjectiveReply& reply, const std::string& title,
                         std::optional<double> source_depth_m = std::nullopt);
plot::Canvas draw_objective(const gram::DepthObjectiveReply& reply, const std::string& title,
                            std::optional<double> source_depth_m = std::nullopt);
inline constexpr plot::Rgb kObjectiveRaw{150, 150, 150}, kObjectiveBest{200, 0, 0}, kObjectiveBelow{235, 235, 235},
    kObjectiveSource{31, 119, 180};

}  // namespace acomms::cli
