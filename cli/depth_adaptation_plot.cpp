#include "depth_adaptation_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <vector>

// stb is not ours to lint. STATIC: gram_plot.cpp has its own copy.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace acomms::cli {
namespace {

constexpr int kWidth = 800, kHeight = 400, kMargin = 20;

struct Rgb {
  std::uint8_t r, g, b;
};

// Red (t = 0) through green to blue (t = 1).
Rgb colour(double t) {
  t = std::clamp(t, 0.0, 1.0);
  auto channel = [](double x) { return static_cast<std::uint8_t>(220 * std::clamp(1.5 - std::abs(x), 0.0, 1.0)); };
  return {channel(4 * (1 - t) - 3), channel(4 * (1 - t) - 2), channel(4 * (1 - t) - 1)};
}

class Canvas {
 public:
  Canvas() : image_(static_cast<std::size_t>(kWidth) * kHeight, Rgb{255, 255, 255}) {}
  void dot(int x, int y, Rgb c, int radius) {
    for (int dy = -radius; dy <= radius; ++dy)
      for (int dx = -radius; dx <= radius; ++dx) {
        const int px = x + dx, py = y + dy;
        if (px >= 0 && px < kWidth && py >= 0 && py < kHeight) image_[static_cast<std::size_t>(py) * kWidth + px] = c;
      }
  }
  void line(int x0, int y0, int x1, int y1, Rgb c, int radius) {
    const int steps = std::max({std::abs(x1 - x0), std::abs(y1 - y0), 1});
    for (int i = 0; i <= steps; ++i)
      dot(x0 + (x1 - x0) * i / steps, y0 + (y1 - y0) * i / steps, c, radius);
  }
  void write(const std::string& path) const {
    if (!stbi_write_png(path.c_str(), kWidth, kHeight, 3, image_.data(), kWidth * 3))
      throw std::runtime_error("cannot write " + path);
  }

 private:
  std::vector<Rgb> image_;
};

}  // namespace

void write_depth_adaptation_png(const std::string& path, const eval::DepthAdaptationResult& result) {
  Canvas canvas;
  const int left = kMargin, right = kWidth - kMargin, top = kMargin, bottom = kHeight - kMargin;
  auto y_of = [&](double p) { return bottom - static_cast<int>(std::lround(p * (bottom - top))); };
  for (int q = 0; q <= 4; ++q) canvas.line(left, y_of(q / 4.0), right, y_of(q / 4.0), {225, 225, 225}, 0);
  canvas.line(left, top, left, bottom, {0, 0, 0}, 0);
  canvas.line(left, bottom, right, bottom, {0, 0, 0}, 0);
  const std::size_t bins = result.bin_edges_m.size() - 1;
  auto x_of = [&](std::size_t b) {
    return left + static_cast<int>(std::lround((b + 0.5) * (right - left) / static_cast<double>(bins)));
  };
  const std::size_t fixed = result.strategies.size() - 1;
  for (std::size_t s = 0; s < result.strategies.size(); ++s) {
    const eval::StrategyResult& strategy = result.strategies[s];
    const bool adaptive = s == fixed;
    const Rgb c = adaptive ? Rgb{0, 0, 0} : colour(fixed > 1 ? double(s) / double(fixed - 1) : 0.0);
    const int width = adaptive ? 2 : 1;
    for (std::size_t b = 0; b < bins; ++b) {
      canvas.dot(x_of(b), y_of(strategy.receipt(b)), c, width + 2);
      if (b > 0) canvas.line(x_of(b - 1), y_of(strategy.receipt(b - 1)), x_of(b), y_of(strategy.receipt(b)), c, width - 1 + 1);
    }
  }
  canvas.write(path);
}

void write_depth_adaptation_sweep_png(const std::string& path, eval::SweepQuantity /*quantity*/,
                                      const std::vector<eval::SweepPoint>& points) {
  Canvas canvas;
  const int left = kMargin, right = kWidth - kMargin, top = kMargin, bottom = kHeight - kMargin;
  auto y_of = [&](double p) { return bottom - static_cast<int>(std::lround(std::clamp(p, 0.0, 1.0) * (bottom - top))); };
  for (int q = 0; q <= 4; ++q) canvas.line(left, y_of(q / 4.0), right, y_of(q / 4.0), {225, 225, 225}, 0);
  canvas.line(left, top, left, bottom, {0, 0, 0}, 0);
  canvas.line(left, bottom, right, bottom, {0, 0, 0}, 0);
  if (points.empty()) return canvas.write(path);
  const double lo = points.front().value, hi = points.back().value;
  auto x_of = [&](double v) {
    const double t = hi > lo ? (v - lo) / (hi - lo) : 0.5;
    return left + 10 + static_cast<int>(std::lround(t * (right - left - 20)));
  };
  // The best fixed depth red, adaptive black; each value's ±1 SE as a bar.
  const Rgb red{200, 30, 30}, black{0, 0, 0};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const eval::SweepPoint& p = points[i];
    const int x = x_of(p.value);
    canvas.line(x + 2, y_of(p.fixed - p.fixed_se), x + 2, y_of(p.fixed + p.fixed_se), red, 0);
    canvas.line(x - 2, y_of(p.adaptive - p.adaptive_se), x - 2, y_of(p.adaptive + p.adaptive_se), black, 0);
    canvas.dot(x + 2, y_of(p.fixed), red, 2);
    canvas.dot(x - 2, y_of(p.adaptive), black, 3);
    if (i > 0) {
      const eval::SweepPoint& q = points[i - 1];
      canvas.line(x_of(q.value) + 2, y_of(q.fixed), x + 2, y_of(p.fixed), red, 0);
      canvas.line(x_of(q.value) - 2, y_of(q.adaptive), x - 2, y_of(p.adaptive), black, 1);
    }
  }
  canvas.write(path);
}

}  // namespace acomms::cli
