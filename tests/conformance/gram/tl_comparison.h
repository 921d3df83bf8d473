// |ΔTL| statistics between a model run and a reference column, pointwise and
// on 400-m range-averaged intensity (README of shared/conformance/gram):
// TL clipped at 120 dB on both sides; receivers at r = 0 ignored.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "csv_table.h"
#include "gram/transmission_loss.h"

namespace acomms::gram::test {

struct DeltaStats {
  double median = 0, p90 = 0, max = 0, within_1db = 0, within_3db = 0;  // fractions in [0, 1]
  std::size_t points = 0;
};

inline std::ostream& operator<<(std::ostream& out, const DeltaStats& s) {
  return out << "median " << s.median << " dB, p90 " << s.p90 << " dB, max " << s.max
             << " dB, within 1 dB " << 100 * s.within_1db << " %, within 3 dB "
             << 100 * s.within_3db << " % (" << s.points << " points)";
}

inline DeltaStats stats_of(std::vector<double> d) {
  DeltaStats s;
  s.points = d.size();
  if (d.empty()) return s;
  std::sort(d.begin(), d.end());
  s.median = d[d.size() / 2];
  s.p90 = d[static_cast<std::size_t>(0.9 * (d.size() - 1))];
  s.max = d.back();
  s.within_1db = static_cast<double>(std::count_if(d.begin(), d.end(), [](double x) { return x <= 1.0; })) / d.size();
  s.within_3db = static_cast<double>(std::count_if(d.begin(), d.end(), [](double x) { return x <= 3.0; })) / d.size();
  return s;
}

inline double clip(double tl) { return std::isnan(tl) ? tl : std::min(tl, 120.0); }

inline std::size_t nearest(const std::vector<double>& v, double x) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (std::abs(v[i] - x) < std::abs(v[best] - x)) best = i;
  return best;
}

struct Comparison {
  DeltaStats pointwise, averaged;
};

// The model on a rectilinear grid against `column` of `table`.
inline Comparison compare(const TransmissionLoss& model, const CsvTable& table, const std::string& column) {
  const std::size_t nr = model.range_m.size();
  std::vector<double> pointwise;
  // Per depth and 400-m bin: summed model and reference intensities, count.
  std::map<std::pair<std::size_t, long>, std::pair<double, double>> bins;
  for (std::size_t row = 0; row < table.size(); ++row) {
    const double r = table.at(row, "range_m"), z = table.at(row, "depth_m");
    if (r <= 0) continue;
    const std::size_t ir = nearest(model.range_m, r), iz = nearest(model.depth_m, z);
    const double got = clip(model.tl_db[iz * nr + ir]), want = clip(table.at(row, column));
    pointwise.push_back(std::abs(got - want));
    auto& bin = bins[{iz, static_cast<long>(std::floor(r / 400.0))}];
    bin.first += std::pow(10.0, -got / 10.0);
    bin.second += std::pow(10.0, -want / 10.0);
  }
  std::vector<double> averaged;
  for (const auto& [key, sums] : bins)
    averaged.push_back(std::abs(10.0 * std::log10(sums.first / sums.second)));
  return {stats_of(pointwise), stats_of(averaged)};
}

}  // namespace acomms::gram::test
