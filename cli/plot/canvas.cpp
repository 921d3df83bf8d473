#include "plot/canvas.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "plot/embedded_font.h"

// stb is not ours to lint.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_TRUETYPE_IMPLEMENTATION
#define STBTT_STATIC
#include <stb/stb_truetype.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace acomms::cli::plot {
namespace {

// DejaVu Sans from fonts-dejavu-core, embedded at build time.
const stbtt_fontinfo& font() {
  static const stbtt_fontinfo info = [] {
    stbtt_fontinfo f{};
    const auto* data = reinterpret_cast<const unsigned char*>(embedded_fonts().at(0).bytes.data());
    if (!stbtt_InitFont(&f, data, stbtt_GetFontOffsetForIndex(data, 0))) throw std::runtime_error("the built-in font does not load");
    return f;
  }();
  return info;
}

// UTF-8 to code points; a bad byte becomes U+FFFD.
std::vector<int> code_points(std::string_view text) {
  std::vector<int> out;
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    int length = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    if (length == 0 || i + length > text.size()) {
      out.push_back(0xFFFD);
      ++i;
      continue;
    }
    int cp = length == 1 ? c : c & (0x7F >> length);
    for (int k = 1; k < length; ++k) cp = (cp << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
    out.push_back(cp);
    i += length;
  }
  return out;
}

}  // namespace

double text_width(std::string_view utf8, double px) {
  const stbtt_fontinfo& f = font();
  const float scale = stbtt_ScaleForPixelHeight(&f, static_cast<float>(px));
  double width = 0;
  const std::vector<int> cps = code_points(utf8);
  for (std::size_t i = 0; i < cps.size(); ++i) {
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&f, cps[i], &advance, &bearing);
    width += advance * scale;
    if (i + 1 < cps.size()) width += stbtt_GetCodepointKernAdvance(&f, cps[i], cps[i + 1]) * scale;
  }
  return width;
}

Canvas::Canvas(int width, int height, Rgb background)
    : width_(width), height_(height), pixels_(static_cast<std::size_t>(width) * height, background) {}

void Canvas::set(int x, int y, Rgb c) {
  if (x >= 0 && x < width_ && y >= 0 && y < height_) pixels_[static_cast<std::size_t>(y) * width_ + x] = c;
}

void Canvas::blend(int x, int y, Rgb c, double alpha) {
  if (x < 0 || x >= width_ || y < 0 || y >= height_ || alpha <= 0) return;
  Rgb& p = pixels_[static_cast<std::size_t>(y) * width_ + x];
  auto mix = [&](std::uint8_t under, std::uint8_t over) {
    return static_cast<std::uint8_t>(std::lround(under + (over - under) * std::min(alpha, 1.0)));
  };
  p = {mix(p.r, c.r), mix(p.g, c.g), mix(p.b, c.b)};
}

void Canvas::fill(int x0, int y0, int x1, int y1, Rgb c) {
  for (int y = std::min(y0, y1); y <= std::max(y0, y1); ++y)
    for (int x = std::min(x0, x1); x <= std::max(x0, x1); ++x) set(x, y, c);
}

void Canvas::line(int x0, int y0, int x1, int y1, Rgb c, int thickness) {
  const int steps = std::max({std::abs(x1 - x0), std::abs(y1 - y0), 1});
  const int before = (thickness - 1) / 2, after = thickness / 2;
  for (int i = 0; i <= steps; ++i) {
    const int x = x0 + (x1 - x0) * i / steps, y = y0 + (y1 - y0) * i / steps;
    fill(x - before, y - before, x + after, y + after, c);
  }
}

void Canvas::text(double x, double y, std::string_view utf8, double px, Rgb c, Align align, bool upwards) {
  const stbtt_fontinfo& f = font();
  const float scale = stbtt_ScaleForPixelHeight(&f, static_cast<float>(px));
  int ascent = 0, descent = 0, gap = 0;
  stbtt_GetFontVMetrics(&f, &ascent, &descent, &gap);
  const double width = text_width(utf8, px);
  double pen = align == Align::kLeft ? 0 : align == Align::kCentre ? -width / 2 : -width;
  // The baseline sits below the anchor by half a capital's height (~0.73 em).
  const double baseline = 0.36 * px;
  const std::vector<int> cps = code_points(utf8);
  for (std::size_t i = 0; i < cps.size(); ++i) {
    int w = 0, h = 0, xoff = 0, yoff = 0;
    unsigned char* bitmap = stbtt_GetCodepointBitmap(&f, scale, scale, cps[i], &w, &h, &xoff, &yoff);
    for (int gy = 0; gy < h; ++gy)
      for (int gx = 0; gx < w; ++gx) {
        const double along = pen + xoff + gx, across = baseline + yoff + gy;  // in the text's own frame
        const int px_x = static_cast<int>(std::lround(upwards ? x + across : x + along));
        const int px_y = static_cast<int>(std::lround(upwards ? y - along : y + across));
        blend(px_x, px_y, c, bitmap[gy * w + gx] / 255.0);
      }
    stbtt_FreeBitmap(bitmap, nullptr);
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&f, cps[i], &advance, &bearing);
    pen += advance * scale;
    if (i + 1 < cps.size()) pen += stbtt_GetCodepointKernAdvance(&f, cps[i], cps[i + 1]) * scale;
  }
}

void Canvas::write_png(const std::string& path) const {
  if (!stbi_write_png(path.c_str(), width_, height_, 3, pixels_.data(), width_ * 3))
    throw std::runtime_error("cannot write " + path);
}

std::string Canvas::png() const {
  std::string out;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &out, width_, height_, 3, pixels_.data(), width_ * 3))
    throw std::runtime_error("cannot encode the picture as PNG");
  return out;
}

}  // namespace acomms::cli::plot
