#include "depth_adaptation_plot.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "plot/axes.h"

namespace acomms::cli {
namespace {

constexpr int kWidth = 900, kHeight = 520;
constexpr int kLeft = 80, kTop = 40, kRight = 700, kBottom = 450;
constexpr int kLegendLeft = 730, kLegendTop = 60, kLegendRow = 22;

// Red (t = 0) through green to blue (t = 1).
plot::Rgb colour(double t) {
  t = std::clamp(t, 0.0, 1.0);
  auto channel = [](double x) { return static_cast<std::uint8_t>(220 * std::clamp(1.5 - std::abs(x), 0.0, 1.0)); };
  return {channel(4 * (1 - t) - 3), channel(4 * (1 - t) - 2), channel(4 * (1 - t) - 1)};
}

}  // namespace

plot::Rgb strategy_colour(const eval::DepthAdaptationResult& result, std::size_t s) {
  const std::size_t fixed = result.strategies.size() - 1;
  if (s == fixed) return plot::kBlack;  // the adaptive strategy, last
  return colour(fixed > 1 ? double(s) / double(fixed - 1) : 0.0);
}

int nodes_note_y(std::size_t legend_rows) { return kLegendTop + static_cast<int>(legend_rows) * kLegendRow + 16; }

namespace {
// The experiment's nodes, under the legend: where the source and the
// receiver are (the picture's axes have no place for them).
void draw_nodes_note(plot::Canvas& canvas, std::size_t legend_rows, double buoy_depth_m) {
  const int y = nodes_note_y(legend_rows);
  canvas.text(kLegendLeft, y, "source: the buoy, " + plot::tick_label(buoy_depth_m, 0.1) + " m", 12, plot::kBlack);
  canvas.text(kLegendLeft, y + 18, "receiver: the vehicle, at", 12, plot::kBlack);
  canvas.text(kLegendLeft, y + 34, "each strategy's depth", 12, plot::kBlack);
}
}  // namespace

int legend_x() { return kLegendLeft + 15; }
int legend_y(std::size_t s) { return kLegendTop + static_cast<int>(s) * kLegendRow; }

plot::Canvas draw_depth_adaptation(const eval::DepthAdaptationResult& result, const std::string& input,
                                   double buoy_depth_m) {
  plot::Canvas canvas(kWidth, kHeight);
  const std::size_t bins = result.bin_edges_m.size() - 1;
  auto centre_km = [&](std::size_t b) { return (result.bin_edges_m[b] + result.bin_edges_m[b + 1]) / 2000; };
  const plot::Frame frame{kLeft, kTop, kRight, kBottom, result.bin_edges_m.front() / 1000,
                          result.bin_edges_m.back() / 1000, 1.0, 0.0};
  plot::draw_axes(canvas, frame, "Range (km)", "Packets received (fraction)", true);
  for (std::size_t s = 0; s < result.strategies.size(); ++s) {
    const eval::StrategyResult& strategy = result.strategies[s];
    const plot::Rgb c = strategy_colour(result, s);
    const int thickness = strategy.fixed_depth_m ? 2 : 3;  // adaptive and forecast stand out
    for (std::size_t b = 0; b < bins; ++b) {
      const int x = frame.x_of(centre_km(b)), y = frame.y_of(strategy.receipt(b));
      canvas.fill(x - 2, y - 2, x + 2, y + 2, c);
      if (b > 0) canvas.line(frame.x_of(centre_km(b - 1)), frame.y_of(strategy.receipt(b - 1)), x, y, c, thickness);
    }
    // The legend: a sample of the line and the strategy's name.
    const int ly = legend_y(s);
    canvas.line(kLegendLeft, ly, kLegendLeft + 30, ly, c, thickness);
    canvas.text(kLegendLeft + 38, ly, strategy.fixed_depth_m ? "fixed at " + strategy.name : strategy.name, 13,
                plot::kBlack);
  }
  canvas.text(kLegendLeft, kLegendTop - 22, "Strategy", 14, plot::kBlack);
  draw_nodes_note(canvas, result.strategies.size(), buoy_depth_m);
  plot::draw_title(canvas, "Depth adaptation: packets received against range, " +
                               std::filesystem::path(input).filename().string());
  return canvas;
}

void write_depth_adaptation_png(const std::string& path, const eval::DepthAdaptationResult& result,
                                const std::string& input, double buoy_depth_m) {
  draw_depth_adaptation(result, input, buoy_depth_m).write_png(path);
}

plot::Canvas draw_depth_adaptation_sweep(eval::SweepQuantity quantity, const std::vector<eval::SweepPoint>& points,
                                         const std::string& input, double buoy_depth_m) {
  plot::Canvas canvas(kWidth, kHeight);
  const double lo = points.empty() ? 0 : points.front().value, hi = points.empty() ? 1 : points.back().value;
  const double pad = hi > lo ? 0 : 1;  // one value: a unit either side
  const plot::Frame frame{kLeft, kTop, kRight, kBottom, lo - pad, hi + pad, 1.0, 0.0};
  const bool noise = quantity == eval::SweepQuantity::kNoise;
  plot::draw_axes(canvas, frame, noise ? "Band noise level NL (dB re 1 uPa)" : "Excess loss (dB)",
                  "Packets received (fraction)", true);
  // Adaptive black, the best fixed depth red; each value's ±1 SE a bar.
  const plot::Rgb red{200, 30, 30};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const eval::SweepPoint& p = points[i];
    const int x = frame.x_of(p.value);
    canvas.line(x + 3, frame.y_of(std::min(1.0, p.fixed + p.fixed_se)), x + 3,
                frame.y_of(std::max(0.0, p.fixed - p.fixed_se)), red, 1);
    canvas.line(x - 3, frame.y_of(std::min(1.0, p.adaptive + p.adaptive_se)), x - 3,
                frame.y_of(std::max(0.0, p.adaptive - p.adaptive_se)), plot::kBlack, 1);
    canvas.fill(x + 1, frame.y_of(p.fixed) - 2, x + 5, frame.y_of(p.fixed) + 2, red);
    canvas.fill(x - 5, frame.y_of(p.adaptive) - 2, x - 1, frame.y_of(p.adaptive) + 2, plot::kBlack);
    if (i > 0) {
      const eval::SweepPoint& q = points[i - 1];
      canvas.line(frame.x_of(q.value) + 3, frame.y_of(q.fixed), x + 3, frame.y_of(p.fixed), red, 2);
      canvas.line(frame.x_of(q.value) - 3, frame.y_of(q.adaptive), x - 3, frame.y_of(p.adaptive), plot::kBlack, 3);
    }
  }
  canvas.text(kLegendLeft, kLegendTop - 22, "Strategy", 14, plot::kBlack);
  canvas.line(kLegendLeft, legend_y(0), kLegendLeft + 30, legend_y(0), plot::kBlack, 3);
  canvas.text(kLegendLeft + 38, legend_y(0), "adaptive", 13, plot::kBlack);
  canvas.line(kLegendLeft, legend_y(1), kLegendLeft + 30, legend_y(1), red, 2);
  canvas.text(kLegendLeft + 38, legend_y(1), "best fixed depth", 13, plot::kBlack);
  canvas.text(kLegendLeft, legend_y(2) + 6, "bars: +-1 standard error", 12, plot::kBlack);
  draw_nodes_note(canvas, 4, buoy_depth_m);
  plot::draw_title(canvas, std::string("Depth adaptation across ") + (noise ? "the noise level" : "the excess loss") +
                               ", " + std::filesystem::path(input).filename().string());
  return canvas;
}

void write_depth_adaptation_sweep_png(const std::string& path, eval::SweepQuantity quantity,
                                      const std::vector<eval::SweepPoint>& points, const std::string& input,
                                      double buoy_depth_m) {
  draw_depth_adaptation_sweep(quantity, points, input, buoy_depth_m).write_png(path);
}

}  // namespace acomms::cli
