#pragma once
// The pictures acommsctl draws (gram tl, gram depth, sim depth-adaptation):
// an RGB raster with lines, filled boxes and text, written as PNG by stb.
// Text is set in DejaVu Sans (built into the binary, text.h), so a picture
// reads the same on every machine.
//
// Thread-safety: a Canvas is a value; one thread per Canvas.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace acomms::cli::plot {

struct Rgb {
  std::uint8_t r, g, b;
  bool operator==(const Rgb&) const = default;
};

inline constexpr Rgb kWhite{255, 255, 255};
inline constexpr Rgb kBlack{0, 0, 0};

// Where text is anchored on its point: its left end, centre or right end;
// vertically on the middle of a capital letter.
enum class Align { kLeft, kCentre, kRight };

class Canvas {
 public:
  Canvas(int width, int height, Rgb background = kWhite);
  int width() const { return width_; }
  int height() const { return height_; }
  Rgb at(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  // Outside the canvas: ignored.
  void set(int x, int y, Rgb c);
  void fill(int x0, int y0, int x1, int y1, Rgb c);  // inclusive corners
  void line(int x0, int y0, int x1, int y1, Rgb c, int thickness = 1);
  // Text of `px` pixels (the font's ascent to descent), horizontal, or
  // turned a quarter counter-clockwise (reading upwards, for a y axis).
  void text(double x, double y, std::string_view utf8, double px, Rgb c, Align align = Align::kLeft,
            bool upwards = false);
  // Throws std::runtime_error naming `path` when it cannot be written.
  void write_png(const std::string& path) const;
  // The PNG file's bytes (the map server sends them without a file).
  std::string png() const;

 private:
  void blend(int x, int y, Rgb c, double alpha);
  int width_, height_;
  std::vector<Rgb> pixels_;
};

// The width of `utf8` set at `px`, in pixels.
double text_width(std::string_view utf8, double px);

}  // namespace acomms::cli::plot
