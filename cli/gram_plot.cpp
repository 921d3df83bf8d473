#include "gram_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "gram/sound_speed_profile.h"
#include "plot/axes.h"

namespace acomms::cli {
namespace {

using plot::Rgb;

// Layout: the field, its colour bar, then the profile; room for the title
// above and the axes' numbers and names around.
constexpr int kWidth = 1100, kHeight = 520;
constexpr plot::Rgb kShadow{220, 220, 220};
constexpr double kDynamicRangeDb = 60.0;
constexpr int kFieldLeft = 80, kFieldRight = 760, kTop = 40, kBottom = 460;
constexpr int kBarLeft = 780, kBarRight = 800;
constexpr int kProfileLeft = 900, kProfileRight = 1080;

// A "jet"-like scale: 0 → dark red (loud), 1 → dark blue (quiet).
Rgb colour(double t) {
  t = std::clamp(1.0 - t, 0.0, 1.0);
  auto channel = [](double x) { return static_cast<std::uint8_t>(255 * std::clamp(1.5 - std::abs(x), 0.0, 1.0)); };
  return {channel(4 * t - 3), channel(4 * t - 2), channel(4 * t - 1)};
}

std::size_t nearest(const std::vector<double>& sorted_or_not, double x) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < sorted_or_not.size(); ++i)
    if (std::abs(sorted_or_not[i] - x) < std::abs(sorted_or_not[best] - x)) best = i;
  return best;
}

void draw_colour_bar(plot::Canvas& canvas, double best) {
  for (int y = kTop; y <= kBottom; ++y) {
    const double db = best + kDynamicRangeDb * (y - kTop) / double(kBottom - kTop);
    canvas.line(kBarLeft, y, kBarRight, y, colour((db - best) / kDynamicRangeDb));
  }
  const plot::Frame bar{kBarLeft, kTop, kBarRight, kBottom, 0, 1, best, best + kDynamicRangeDb};
  const std::vector<double> ticks = plot::nice_ticks(best, best + kDynamicRangeDb, 6);
  for (double db : ticks) {
    canvas.line(kBarRight, bar.y_of(db), kBarRight + 4, bar.y_of(db), plot::kBlack);
    canvas.text(kBarRight + 7, bar.y_of(db), plot::tick_label(db, ticks.size() > 1 ? ticks[1] - ticks[0] : 1), 12,
                plot::kBlack);
  }
  canvas.text(kBarRight + 46, (kTop + kBottom) / 2.0, "TL (dB re 1 m)", 14, plot::kBlack, plot::Align::kCentre, true);
}

plot::Frame field_frame(const gram::TransmissionLoss& tl, const gram::Environment& env) {
  const auto [r_min, r_max] = std::minmax_element(tl.range_m.begin(), tl.range_m.end());
  const double z_top = env.sound_speed(0).depth_m();
  const double z_bottom = env.sound_speed(env.sound_speed_size() - 1).depth_m();
  return {kFieldLeft, kTop, kFieldRight, kBottom, *r_min / 1000, *r_max / 1000, z_top, z_bottom};
}

// A filled shape ringed in white, `inner` pixels from its centre to its edge.
void ringed(plot::Canvas& canvas, int cx, int cy, int inner, bool round) {
  for (int r = inner + 3; r >= 0; --r)
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx)
        if (!round || dx * dx + dy * dy <= r * r) canvas.set(cx + dx, cy + dy, r > inner ? plot::kWhite : plot::kBlack);
}

// Labels on the field stay inside it: to the right of the mark, or to its
// left near the right edge.
void mark_label(plot::Canvas& canvas, int x, int y, const std::string& label) {
  const double width = plot::text_width(label, 12);
  const bool left = x + 10 + width > kFieldRight;
  const double tx = left ? x - 10 : x + 10;
  const plot::Align align = left ? plot::Align::kRight : plot::Align::kLeft;
  const double x0 = left ? tx - width : tx;
  canvas.fill(static_cast<int>(x0) - 2, y - 8, static_cast<int>(x0 + width) + 2, y + 7, plot::kWhite);
  canvas.text(tx, y, label, 12, plot::kBlack, align);
}

}  // namespace

std::pair<int, int> tl_pixel(const gram::TransmissionLoss& tl, const gram::Environment& env, double range_m,
                             double depth_m) {
  const plot::Frame f = field_frame(tl, env);
  return {f.x_of(range_m / 1000), f.y_of(depth_m)};
}

Rgb tl_colour(double db, double best_db) { return colour((db - best_db) / kDynamicRangeDb); }
int tl_colour_bar_x() { return (kBarLeft + kBarRight) / 2; }
int tl_colour_bar_y(double db, double best_db) {
  return kTop + static_cast<int>(std::lround((db - best_db) / kDynamicRangeDb * (kBottom - kTop)));
}

plot::Canvas draw_tl(const gram::TransmissionLoss& tl, const gram::Environment& env, const std::string& input,
                     const TlMarks& marks) {
  if (tl.irregular) throw std::runtime_error("--png needs a rectilinear receiver grid");
  plot::Canvas canvas(kWidth, kHeight);
  double best = INFINITY;
  for (double v : tl.tl_db)
    if (std::isfinite(v)) best = std::min(best, v);
  if (!std::isfinite(best)) best = 0;
  best = std::floor(best);  // the bar starts on a whole dB
  const auto [r_min, r_max] = std::minmax_element(tl.range_m.begin(), tl.range_m.end());
  const double z_top = env.sound_speed(0).depth_m();
  const double z_bottom = env.sound_speed(env.sound_speed_size() - 1).depth_m();
  const std::size_t nr = tl.range_m.size();
  const int w = kFieldRight - kFieldLeft, h = kBottom - kTop;
  // Nearest receiver per pixel column and row (receiver lists are short).
  std::vector<std::size_t> column_of(w), row_of(h);
  for (int x = 0; x < w; ++x) column_of[x] = nearest(tl.range_m, *r_min + (*r_max - *r_min) * (x + 0.5) / w);
  for (int y = 0; y < h; ++y) row_of[y] = nearest(tl.depth_m, z_top + (z_bottom - z_top) * (y + 0.5) / h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double v = tl.tl_db[row_of[y] * nr + column_of[x]];
      canvas.set(kFieldLeft + x, kTop + y, std::isfinite(v) ? colour((v - best) / kDynamicRangeDb) : kShadow);
    }
  const plot::Frame field = field_frame(tl, env);
  plot::draw_axes(canvas, field, "Range (km)", "Depth (m)");
  // The receiver first: its depth as a dotted line across the field, then
  // its mark, so that the source's mark stays whole when they are close.
  if (marks.receiver) {
    const int rx = field.x_of(marks.receiver->range_m / 1000), ry = field.y_of(marks.receiver->depth_m);
    for (int x = kFieldLeft; x <= kFieldRight; x += 6) canvas.line(x, ry, std::min(x + 2, kFieldRight), ry, plot::kWhite);
    ringed(canvas, rx, ry, 4, false);
    mark_label(canvas, rx, ry - 14, marks.receiver->label);
  }
  // The source: a dot ringed in white at range 0 and its depth.
  const int sx = field.x_of(0), sy = field.y_of(env.source_depth_m());
  ringed(canvas, sx, sy, 4, true);
  mark_label(canvas, sx, sy, marks.source);
  draw_colour_bar(canvas, best);

  // The profile: c across, the same depths down.
  const gram::SoundSpeedProfile ssp(env);
  std::vector<double> speed(h);
  for (int y = 0; y < h; ++y) {
    const double z = z_top + (z_bottom - z_top) * (y + 0.5) / h;
    speed[y] = ssp.at(z, ssp.layer_at(z, 1.0)).c;
  }
  const auto [c_min, c_max] = std::minmax_element(speed.begin(), speed.end());
  const double pad = std::max((*c_max - *c_min) * 0.1, 1.0);
  const plot::Frame profile{kProfileLeft, kTop, kProfileRight, kBottom, *c_min - pad, *c_max + pad, z_top, z_bottom};
  plot::draw_axes(canvas, profile, "Sound speed (m/s)", "", true);  // the field's depth axis names both
  for (int y = 1; y < h; ++y)
    canvas.line(profile.x_of(speed[y - 1]), kTop + y - 1, profile.x_of(speed[y]), kTop + y, plot::kBlack, 2);

  char frequency[32];
  std::snprintf(frequency, sizeof frequency, "%g Hz", env.frequency_hz());
  const std::string name = std::filesystem::path(input).filename().string();
  plot::draw_title(canvas, "Transmission loss of " + name + (env.title().empty() ? "" : " (" + env.title() + ")") +
                               ", " + frequency + ", source at " + plot::tick_label(env.source_depth_m(), 0.1) + " m");
  return canvas;
}

void write_tl_png(const std::string& path, const gram::TransmissionLoss& tl, const gram::Environment& env,
                  const std::string& input, const TlMarks& marks) {
  draw_tl(tl, env, input, marks).write_png(path);
}

plot::Canvas draw_objective(const gram::DepthObjectiveReply& reply, const std::string& title,
                            std::optional<double> source_depth_m) {
  constexpr int kW = 700, kH = 520;
  const auto& points = reply.points();
  if (points.empty()) throw std::runtime_error("no depths to plot");
  const double z_top = points[0].depth_m(), z_bottom = std::max(points[points.size() - 1].depth_m(), z_top + 1);
  plot::Canvas canvas(kW, kH);
  const plot::Frame f{80, 40, 460, 460, 0.0, 1.0, z_top, z_bottom};
  // Not allowed: beyond the best-depth search's deepest allowed depth.
  for (const auto& p : points)
    if (p.depth_m() > reply.bottom_m()) canvas.fill(f.left, f.y_of(p.depth_m()) - 1, f.right, f.y_of(p.depth_m()) + 1, kObjectiveBelow);
  plot::draw_axes(canvas, f, "Objective (0 to 1)", "Depth (m)", true);
  for (int i = 1; i < points.size(); ++i) {
    const auto& a = points[i - 1];
    const auto& b = points[i];
    canvas.line(f.x_of(a.objective()), f.y_of(a.depth_m()), f.x_of(b.objective()), f.y_of(b.depth_m()), kObjectiveRaw);
    canvas.line(f.x_of(a.objective_filtered()), f.y_of(a.depth_m()), f.x_of(b.objective_filtered()), f.y_of(b.depth_m()),
                plot::kBlack, 2);
  }
  const bool source_shown = source_depth_m && *source_depth_m >= z_top && *source_depth_m <= z_bottom;
  if (source_shown) {
    const int y = f.y_of(*source_depth_m);
    for (int x = f.left; x <= f.right; x += 12) canvas.line(x, y, std::min(x + 7, f.right), y, kObjectiveSource, 2);
  }
  canvas.line(f.left, f.y_of(reply.best_depth_m()), f.right, f.y_of(reply.best_depth_m()), kObjectiveBest, 3);
  const int lx = 480, ly = 60;
  canvas.line(lx, ly, lx + 30, ly, kObjectiveRaw);
  canvas.text(lx + 38, ly, "objective", 13, plot::kBlack);
  canvas.line(lx, ly + 22, lx + 30, ly + 22, plot::kBlack, 2);
  canvas.text(lx + 38, ly + 22, "filtered", 13, plot::kBlack);
  canvas.line(lx, ly + 44, lx + 30, ly + 44, kObjectiveBest, 3);
  canvas.text(lx + 38, ly + 44, "receiver's best depth " + plot::tick_label(reply.best_depth_m(), 0.1) + " m", 13,
              plot::kBlack);
  canvas.fill(lx, ly + 61, lx + 30, ly + 71, kObjectiveBelow);
  canvas.text(lx + 38, ly + 66, "below the bottom", 13, plot::kBlack);
  if (source_shown) {
    for (int x = lx; x <= lx + 30; x += 12) canvas.line(x, ly + 88, std::min(x + 7, lx + 30), ly + 88, kObjectiveSource, 2);
    canvas.text(lx + 38, ly + 88, "source (other node) " + plot::tick_label(*source_depth_m, 0.1) + " m", 13,
                plot::kBlack);
  }
  plot::draw_title(canvas, title);
  return canvas;
}

void write_objective_png(const std::string& path, const gram::DepthObjectiveReply& reply, const std::string& title,
                         std::optional<double> source_depth_m) {
  draw_objective(reply, title, source_depth_m).write_png(path);
}

}  // namespace acomms::cli
