#include "link_calibration_plot.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "plot/axes.h"

namespace acomms::cli {
namespace {

constexpr int kWidth = 1200, kHeight = 560;
constexpr int kTop = 50, kBottom = 470;
constexpr int kLeftA = 80, kRightA = 520, kLeftB = 620, kRightB = 1060;
constexpr int kLegendLeft = 80, kLegendTop = 520, kLegendColumn = 260;

const plot::Rgb kPalette[] = {{30, 90, 200}, {200, 40, 40}, {30, 150, 60}, {150, 60, 170}, {220, 130, 0}, {0, 150, 160}};
const plot::Rgb kGrey{150, 150, 150};

plot::Rgb colour_of(std::size_t i) { return kPalette[i % std::size(kPalette)]; }

void dot(plot::Canvas& canvas, int x, int y, plot::Rgb c) { canvas.fill(x - 2, y - 2, x + 2, y + 2, c); }

void dashed(plot::Canvas& canvas, const plot::Frame& f, double x0, double y0, double x1, double y1, plot::Rgb c) {
  constexpr int kDashes = 40;
  for (int i = 0; i < kDashes; i += 2) {
    const double t0 = double(i) / kDashes, t1 = double(i + 1) / kDashes;
    canvas.line(f.x_of(x0 + t0 * (x1 - x0)), f.y_of(y0 + t0 * (y1 - y0)), f.x_of(x0 + t1 * (x1 - x0)),
                f.y_of(y0 + t1 * (y1 - y0)), c, 2);
  }
}

}  // namespace

plot::Canvas draw_link_calibration(const std::vector<eval::PacketSample>& samples,
                                   const std::vector<eval::LinkCalibration>& links) {
  plot::Canvas canvas(kWidth, kHeight);
  double lo = INFINITY, hi = -INFINITY;
  for (const eval::PacketSample& s : samples) {
    lo = std::min({lo, s.predicted_snr_db, s.measured_snr_db.value_or(s.predicted_snr_db)});
    hi = std::max({hi, s.predicted_snr_db, s.measured_snr_db.value_or(s.predicted_snr_db)});
  }
  if (!(hi > lo)) {
    lo = std::isfinite(lo) ? lo - 1 : 0;
    hi = lo + 2;
  }
  lo = std::floor(lo) - 1;
  hi = std::ceil(hi) + 1;
  const plot::Frame a{kLeftA, kTop, kRightA, kBottom, lo, hi, hi, lo};
  const plot::Frame b{kLeftB, kTop, kRightB, kBottom, lo, hi, 1.0, 0.0};
  plot::draw_axes(canvas, a, "Predicted SNR, SL - TL - NL (dB)", "Measured SNR (dB)", true);
  plot::draw_axes(canvas, b, "Predicted SNR, SL - TL - NL (dB)", "Packets decoded (fraction)", true);
  canvas.line(a.x_of(lo), a.y_of(lo), a.x_of(hi), a.y_of(hi), kGrey, 1);

  // One colour per (link, rate); the left panel uses each link's first.
  std::size_t next = 0;
  std::map<std::pair<int32_t, int32_t>, std::size_t> colour;
  for (const eval::LinkCalibration& link : links) {
    for (const auto& [rate, r] : link.rates) colour[{link.src, rate}] = next++;
  }
  for (const eval::PacketSample& s : samples) {
    if (s.measured_snr_db) dot(canvas, a.x_of(s.predicted_snr_db), a.y_of(*s.measured_snr_db), colour_of(colour[{s.src, s.rate}]));
  }
  // Fraction decoded per 1 dB bin of predicted SNR.
  std::map<std::tuple<int32_t, int32_t, int>, std::pair<int, int>> bins;  // decoded, all
  for (const eval::PacketSample& s : samples) {
    auto& bin = bins[{s.src, s.rate, static_cast<int>(std::floor(s.predicted_snr_db))}];
    bin.first += s.decoded ? 1 : 0;
    ++bin.second;
  }
  for (const auto& [key, counts] : bins) {
    const auto [src, rate, db] = key;
    dot(canvas, b.x_of(db + 0.5), b.y_of(double(counts.first) / counts.second), colour_of(colour[{src, rate}]));
  }
  int legend = 0;
  for (const eval::LinkCalibration& link : links) {
    for (const auto& [rate, r] : link.rates) {
      const plot::Rgb c = colour_of(colour[{link.src, rate}]);
      if (link.excess) {
        // measured = predicted + offset, only where it stays inside the frame.
        const double offset = link.offset_db();  // the censored fit's where it fitted
        const double x0 = std::max(lo, lo - offset), x1 = std::min(hi, hi - offset);
        if (x1 > x0) dashed(canvas, a, x0, x0 + offset, x1, x1 + offset, c);
      }
      if (r.curve) {
        int px = -1, py = -1;
        for (int i = 0; i <= 200; ++i) {
          const double x = lo + (hi - lo) * i / 200;
          const double p = 1 / (1 + std::exp(-r.curve->slope_per_db * (x - r.curve->snr50_predicted_db)));
          const int qx = b.x_of(x), qy = b.y_of(p);
          if (px >= 0) canvas.line(px, py, qx, qy, c, 2);
          px = qx;
          py = qy;
        }
      }
      const int lx = kLegendLeft + (legend % 4) * kLegendColumn, ly = kLegendTop + (legend / 4) * 20;
      canvas.fill(lx, ly - 4, lx + 8, ly + 4, c);
      canvas.text(lx + 14, ly,
                  (link.link.empty() ? "" : link.link + ": ") + "from modem " + std::to_string(link.src) + ", rate " +
                      std::to_string(rate),
                  13,
                  plot::kBlack);
      ++legend;
    }
  }
  plot::draw_title(canvas, "Link calibration: measured against predicted SNR (left, grey 1:1, dashed the fitted "
                           "offset); decoding against predicted SNR (right)");
  return canvas;
}

void write_link_calibration_png(const std::string& path, const std::vector<eval::PacketSample>& samples,
                                const std::vector<eval::LinkCalibration>& links) {
  draw_link_calibration(samples, links).write_png(path);
}

}  // namespace acomms::cli
