// Range-averaged TL and the instance average: shared/spec/gram.md §6.2, §6.3.
#include "gram/range_averaged_tl.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gram/validation_text.h"

namespace acomms::gram {
namespace {

constexpr double kEdgeTolerance_m = 1e-6;
constexpr double kInf = std::numeric_limits<double>::infinity();

double intensity(double tl_db) { return std::pow(10.0, -tl_db / 10.0); }  // +inf → 0

double to_db(double intensity) { return intensity > 0 ? -10.0 * std::log10(intensity) : kInf; }

void require_grid(const TransmissionLoss& tl) {
  if (tl.irregular)
    throw std::invalid_argument(
        "the range-averaged TL needs a rectilinear receiver grid, not irregular receivers");
  if (tl.tl_db.size() != tl.range_m.size() * tl.depth_m.size())
    throw std::invalid_argument("tl_db has " + std::to_string(tl.tl_db.size()) +
                                " values; the grid has " + std::to_string(tl.depth_m.size()) +
                                " depths x " + std::to_string(tl.range_m.size()) + " ranges");
}

}  // namespace

double grid_range_step(const TransmissionLoss& tl) {
  if (tl.range_m.size() < 2)
    throw std::invalid_argument("the receiver grid has " + std::to_string(tl.range_m.size()) +
                                " range(s); at least 2 are needed for a range spacing");
  double step = kInf;
  for (std::size_t j = 1; j < tl.range_m.size(); ++j) {
    const double d = tl.range_m[j] - tl.range_m[j - 1];
    if (!(d > 0))
      throw std::invalid_argument("receiver range_m[" + std::to_string(j) +
                                  "] = " + format_number(tl.range_m[j]) +
                                  " must be greater than range_m[" + std::to_string(j - 1) +
                                  "] = " + format_number(tl.range_m[j - 1]));
    step = std::min(step, d);
  }
  return step;
}

RangeAveragedTl range_averaged_tl(const TransmissionLoss& tl, const RangeWindow& window) {
  require_grid(tl);
  std::vector<std::size_t> columns;
  for (std::size_t j = 0; j < tl.range_m.size(); ++j) {
    const double r = tl.range_m[j];
    if (r >= window.begin_m - kEdgeTolerance_m && r < window.end_m - kEdgeTolerance_m)
      columns.push_back(j);
  }
  if (columns.empty()) {
    const std::string span = tl.range_m.empty() ? "none"
                                                : format_number(tl.range_m.front()) + " to " +
                                                      format_number(tl.range_m.back()) + " m";
    throw std::invalid_argument("the range window [" + format_number(window.begin_m) + ", " +
                                format_number(window.end_m) +
                                ") m holds no receiver range (grid ranges: " + span + ")");
  }
  RangeAveragedTl out;
  out.depth_m = tl.depth_m;
  out.ranges_in_window = columns.size();
  const std::size_t n_ranges = tl.range_m.size();
  for (std::size_t i = 0; i < tl.depth_m.size(); ++i) {
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t j : columns) {
      const double t = tl.tl_db[i * n_ranges + j];
      if (std::isnan(t)) continue;  // range 0: the model gives no value there
      sum += intensity(t);
      ++count;
    }
    out.h_bar_db.push_back(count ? to_db(sum / static_cast<double>(count)) : kInf);
  }
  return out;
}

InstanceAverage average_over_instances(std::span<const double> h_db) {
  if (h_db.empty()) throw std::invalid_argument("the instance average needs at least 1 H value");
  double mean = 0.0;
  for (std::size_t i = 0; i < h_db.size(); ++i) {
    if (std::isnan(h_db[i]))
      throw std::invalid_argument("H[" + std::to_string(i) + "] is not a number");
    mean += intensity(h_db[i]);
  }
  const double n = static_cast<double>(h_db.size());
  mean /= n;
  double variance = 0.0;
  for (double h : h_db) variance += (intensity(h) - mean) * (intensity(h) - mean);
  const double sigma = std::sqrt(variance / n);
  InstanceAverage a;
  a.h_n_db = to_db(mean);
  a.band_low_db = to_db(mean + sigma);
  const double floor = std::pow(10.0, -kBandFloorDb / 10.0);
  a.band_high_db = std::min(to_db(std::max(mean - sigma, floor)), kBandFloorDb);
  if (mean == 0) a.band_high_db = kInf;  // every instance in shadow: no band
  return a;
}

}  // namespace acomms::gram
