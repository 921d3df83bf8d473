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

}  // namespace

Rgb tl_colour(double db, double best_db) { return colour((db - best_db) / kDynamicRangeDb); }
int tl_colour_bar_x() { return (kBarLeft + kBarRight) / 2; }
int tl_colour_bar_y(double db, double best_db) {
  return kTop + static_cast<int>(std::lround((db - best_db) / kDynamicRangeDb * (kBottom - kTop)));
}

plot::Canvas draw_tl(const gram::TransmissionLoss& tl, const gram::Environment& env, const std::string& input) {
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
  const plot::Frame field{kFieldLeft, kTop, kFieldRight, kBottom, *r_min / 1000, *r_max / 1000, z_top, z_bottom};
  plot::draw_axes(canvas, field, "Range (km)", "Depth (m)");
  // The source: a dot ringed in white at range 0 and its depth.
  const int sx = field.x_of(0), sy = field.y_of(env.source_depth_m());
  for (int r = 7; r >= 0; --r)
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx)
        if (dx * dx + dy * dy <= r * r) canvas.set(sx + dx, sy + dy, r > 4 ? plot::kWhite : plot::kBlack);
  canvas.text(sx + 10, sy, "source", 12, plot::kBlack);
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
                  const std::string& input) {
  draw_tl(tl, env, input).write_png(path);
}

void write_objective_png(const std::string& path, const gram::DepthObjectiveReply& reply) {
  constexpr int kWidth = 400, kHeight = 400;
  const auto& points = reply.points();
  if (points.empty()) throw std::runtime_error("no depths to plot");
  const double z_top = points[0].depth_m(), z_bottom = points[points.size() - 1].depth_m();
  const double span = std::max(z_bottom - z_top, 1.0);
  std::vector<Rgb> image(static_cast<std::size_t>(kWidth) * kHeight, Rgb{255, 255, 255});
  auto pixel = [&](int x, int y) -> Rgb& {
    return image[static_cast<std::size_t>(std::clamp(y, 0, kHeight - 1)) * kWidth + std::clamp(x, 0, kWidth - 1)];
  };
  auto row = [&](double z) { return static_cast<int>((z - z_top) / span * (kHeight - 1)); };
  auto column = [&](double o) { return static_cast<int>(std::clamp(o, 0.0, 1.0) * (kWidth - 1)); };
  // Not allowed: beyond the best-depth search's deepest allowed depth.
  for (const auto& p : points)
    if (p.depth_m() > reply.bottom_m())
      for (int x = 0; x < kWidth; ++x) pixel(x, row(p.depth_m())) = {235, 235, 235};
  for (int i = 1; i < points.size(); ++i) {
    const int y0 = row(points[i - 1].depth_m()), y1 = row(points[i].depth_m());
    for (int y = y0; y <= y1; ++y) {
      const double t = y1 == y0 ? 1.0 : double(y - y0) / (y1 - y0);
      auto at = [&](double a, double b) { return column(a + t * (b - a)); };
      pixel(at(points[i - 1].objective(), points[i].objective()), y) = {150, 150, 150};
      const int x = at(points[i - 1].objective_filtered(), points[i].objective_filtered());
      for (int dx = -1; dx <= 1; ++dx) pixel(x + dx, y) = {0, 0, 0};
    }
  }
  const int best = row(reply.best_depth_m());
  for (int x = 0; x < kWidth; ++x)
    for (int dy = -1; dy <= 1; ++dy) pixel(x, best + dy) = {200, 0, 0};
  plot::Canvas canvas(kWidth, kHeight);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const Rgb& c = image[static_cast<std::size_t>(y) * kWidth + x];
      canvas.set(x, y, c);
    }
  canvas.write_png(path);
}

}  // namespace acomms::cli
