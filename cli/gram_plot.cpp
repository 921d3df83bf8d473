#include "gram_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "gram/sound_speed_profile.h"

// stb is not ours to lint.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wsign-compare"
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace acomms::cli {
namespace {

constexpr int kFieldWidth = 800, kHeight = 400, kGap = 8, kProfileWidth = 160;
constexpr double kDynamicRangeDb = 60.0;

struct Rgb {
  std::uint8_t r, g, b;
};

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

}  // namespace

void write_tl_png(const std::string& path, const gram::TransmissionLoss& tl, const gram::Environment& env) {
  if (tl.irregular) throw std::runtime_error("--png needs a rectilinear receiver grid");
  const int width = kFieldWidth + kGap + kProfileWidth;
  std::vector<Rgb> image(static_cast<std::size_t>(width) * kHeight, Rgb{255, 255, 255});
  auto pixel = [&](int x, int y) -> Rgb& { return image[static_cast<std::size_t>(y) * width + x]; };

  double best = INFINITY;
  for (double v : tl.tl_db)
    if (std::isfinite(v)) best = std::min(best, v);
  const auto [r_min, r_max] = std::minmax_element(tl.range_m.begin(), tl.range_m.end());
  const double z_top = env.sound_speed(0).depth_m();
  const double z_bottom = env.sound_speed(env.sound_speed_size() - 1).depth_m();
  const std::size_t nr = tl.range_m.size();
  // Nearest receiver per pixel column and row (receiver lists are short).
  std::vector<std::size_t> column_of(kFieldWidth), row_of(kHeight);
  for (int x = 0; x < kFieldWidth; ++x)
    column_of[x] = nearest(tl.range_m, *r_min + (*r_max - *r_min) * (x + 0.5) / kFieldWidth);
  for (int y = 0; y < kHeight; ++y)
    row_of[y] = nearest(tl.depth_m, z_top + (z_bottom - z_top) * (y + 0.5) / kHeight);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kFieldWidth; ++x) {
      const double v = tl.tl_db[row_of[y] * nr + column_of[x]];
      pixel(x, y) = std::isfinite(v) ? colour((v - best) / kDynamicRangeDb) : Rgb{220, 220, 220};
    }

  // The profile: c on the horizontal axis, the same depths down.
  const gram::SoundSpeedProfile ssp(env);
  std::vector<double> speed(kHeight);
  for (int y = 0; y < kHeight; ++y) {
    const double z = z_top + (z_bottom - z_top) * (y + 0.5) / kHeight;
    speed[y] = ssp.at(z, ssp.layer_at(z, 1.0)).c;
  }
  const auto [c_min, c_max] = std::minmax_element(speed.begin(), speed.end());
  const double span = std::max(*c_max - *c_min, 1.0);
  const int x0 = kFieldWidth + kGap + 4;
  for (int y = 0; y < kHeight; ++y) {
    pixel(kFieldWidth + kGap, y) = {0, 0, 0};  // the profile's axis
    const int x = x0 + static_cast<int>((speed[y] - *c_min) / span * (kProfileWidth - 10));
    for (int dx = -1; dx <= 1; ++dx) pixel(std::clamp(x + dx, x0, width - 1), y) = {0, 0, 0};
  }
  if (!stbi_write_png(path.c_str(), width, kHeight, 3, image.data(), width * 3))
    throw std::runtime_error("cannot write " + path);
}

void write_objective_png(const std::string& path, const gram::DepthObjectiveReply& reply) {
  constexpr int kWidth = 400;
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
  if (!stbi_write_png(path.c_str(), kWidth, kHeight, 3, image.data(), kWidth * 3))
    throw std::runtime_error("cannot write " + path);
}

}  // namespace acomms::cli
