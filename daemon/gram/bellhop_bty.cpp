// .bty import: shared/spec/gram.md §7.3, §7.4.
#include "gram/bellhop_import.h"

namespace acomms::gram {

std::vector<BathymetryPoint> import_bellhop_bty(std::string_view text, const std::string& name) {
  ListDirectedReader in(text, name);
  const auto kind = in.next_record(1, 1, "the interpolation option ('L' or 'C')");
  const std::string opt = kind.values[0].text;
  if (opt.empty() || (opt[0] != 'L' && opt[0] != 'C'))
    in.fail(kind.line, "interpolation option '" + opt + "' is not 'L' (linear) or 'C'");
  if (opt[0] == 'C')
    in.fail(kind.line, "curvilinear ('C') boundaries are not supported: they need boundary "
                       "curvature terms in the dynamic ray equations; use 'L'");
  if (opt.size() > 1 && opt[1] == 'L')
    in.fail(kind.line, "long format ('LL', per-point geo-acoustic values) is not supported");
  if (opt.size() > 1 && opt[1] != ' ' && opt[1] != 'S')
    in.fail(kind.line, "format option '" + opt.substr(1, 1) + "' is not known");
  const auto count_record = in.next_record(1, 1, "the number of points");
  const double count = in.number(count_record.values[0], "the number of points", count_record.line);
  if (!(count >= 2 && count <= 1'000'000) || count != static_cast<long>(count))
    in.fail(count_record.line, "the number of points must be an integer in [2, 1000000]");
  std::vector<BathymetryPoint> points;
  for (long i = 0; i < static_cast<long>(count); ++i) {
    const auto row = in.next_record(2, 2, "point " + std::to_string(i + 1) + " (range km, depth m)");
    if (row.values.size() < 2) in.fail(row.line, "point " + std::to_string(i + 1) + " needs a range and a depth");
    BathymetryPoint p;
    p.set_range_m(1000.0 * in.number(row.values[0], "range", row.line));
    p.set_depth_m(in.number(row.values[1], "depth", row.line));
    if (!points.empty() && !(p.range_m() > points.back().range_m()))
      in.fail(row.line, "ranges must be strictly increasing");
    points.push_back(p);
  }
  return points;
}

}  // namespace acomms::gram
