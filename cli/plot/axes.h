#pragma once
// Axes for acommsctl's pictures: a frame around a plot area, ticks at
// "nice" values (1, 2 or 5 times a power of ten) with their numbers, and
// each axis's name with its unit, so that a reader can read values off the
// picture without the command's text output.
//
// Thread-safety: pure functions on the caller's Canvas.

#include <string>
#include <vector>

#include "plot/canvas.h"

namespace acomms::cli::plot {

// A plot area on the canvas (pixels, inclusive) and the values at its edges.
struct Frame {
  int left, top, right, bottom;
  double x_min, x_max;  // at left, right
  double y_top, y_bottom;  // at top, bottom (depth grows downwards: y_top < y_bottom)
  int x_of(double x) const;
  int y_of(double y) const;
};

// About `count` nice values covering [lo, hi] (only those inside it).
std::vector<double> nice_ticks(double lo, double hi, int count);
// A tick's number with as many decimals as the ticks' step needs.
std::string tick_label(double value, double step);

// The frame, ticks (and light grid lines when `grid`), their numbers, and
// the axes' names below and to the left.
void draw_axes(Canvas& canvas, const Frame& frame, const std::string& x_name, const std::string& y_name,
               bool grid = false);

// The picture's title, centred on top.
void draw_title(Canvas& canvas, const std::string& title);

}  // namespace acomms::cli::plot
