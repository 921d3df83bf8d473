#include "plot/axes.h"

#include <cmath>
#include <cstdio>

namespace acomms::cli::plot {
namespace {

constexpr double kTickPx = 12, kNamePx = 14, kTitlePx = 16;
constexpr Rgb kGrid{225, 225, 225};

}  // namespace

int Frame::x_of(double x) const {
  return left + static_cast<int>(std::lround((x - x_min) / (x_max - x_min) * (right - left)));
}

int Frame::y_of(double y) const {
  return top + static_cast<int>(std::lround((y - y_top) / (y_bottom - y_top) * (bottom - top)));
}

std::vector<double> nice_ticks(double lo, double hi, int count) {
  if (lo > hi) std::swap(lo, hi);
  const double span = hi - lo > 0 ? hi - lo : std::max(std::abs(lo), 1.0);
  const double raw = span / std::max(count, 1);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * power;
    if (step >= raw) break;
  }
  std::vector<double> out;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step) out.push_back(v == 0 ? 0 : v);
  return out;
}

std::string tick_label(double value, double step) {
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  char text[40];
  std::snprintf(text, sizeof text, "%.*f", decimals, std::abs(value) < step * 1e-9 ? 0.0 : value);
  return text;
}

void draw_axes(Canvas& canvas, const Frame& f, const std::string& x_name, const std::string& y_name, bool grid) {
  const std::vector<double> xs = nice_ticks(f.x_min, f.x_max, 6);
  const std::vector<double> ys = nice_ticks(f.y_top, f.y_bottom, 8);
  const double x_step = xs.size() > 1 ? xs[1] - xs[0] : 1, y_step = ys.size() > 1 ? ys[1] - ys[0] : 1;
  for (double x : xs) {
    const int px = f.x_of(x);
    if (grid) canvas.line(px, f.top, px, f.bottom, kGrid);
    canvas.line(px, f.bottom, px, f.bottom + 5, kBlack);
    canvas.text(px, f.bottom + 15, tick_label(x, x_step), kTickPx, kBlack, Align::kCentre);
  }
  double widest = 0;
  for (double y : ys) {
    const int py = f.y_of(y);
    if (grid) canvas.line(f.left, py, f.right, py, kGrid);
    canvas.line(f.left - 5, py, f.left, py, kBlack);
    const std::string label = tick_label(y, y_step);
    widest = std::max(widest, text_width(label, kTickPx));
    canvas.text(f.left - 8, py, label, kTickPx, kBlack, Align::kRight);
  }
  canvas.line(f.left, f.top, f.right, f.top, kBlack);
  canvas.line(f.left, f.bottom, f.right, f.bottom, kBlack);
  canvas.line(f.left, f.top, f.left, f.bottom, kBlack);
  canvas.line(f.right, f.top, f.right, f.bottom, kBlack);
  canvas.text((f.left + f.right) / 2.0, f.bottom + 34, x_name, kNamePx, kBlack, Align::kCentre);
  if (!y_name.empty()) {
    canvas.text(f.left - 14 - widest - 10, (f.top + f.bottom) / 2.0, y_name, kNamePx, kBlack, Align::kCentre, true);
  }
}

void draw_title(Canvas& canvas, const std::string& title) {
  canvas.text(canvas.width() / 2.0, 16, title, kTitlePx, kBlack, Align::kCentre);
}

}  // namespace acomms::cli::plot
