// CTD cast to sound speed profile: shared/spec/gram.md §2.6.
#include "gram/ctd_cast.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>

#include "gram/pressure.h"
#include "gram/salinity.h"
#include "gram/sound_speed.h"

namespace acomms::gram {
namespace {

std::vector<std::string> split(std::string_view line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    std::string cell(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\r' || cell.back() == '\t')) cell.pop_back();
    while (!cell.empty() && (cell.front() == ' ' || cell.front() == '\t')) cell.erase(0, 1);
    cells.push_back(cell);
    if (comma == std::string_view::npos) return cells;
    start = comma + 1;
  }
}

std::optional<std::size_t> column(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return i;
  return std::nullopt;
}

}  // namespace

std::vector<CtdSample> read_ctd_csv(std::string_view text, const std::string& name) {
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  if (lines.empty()) throw ImportError(name + ": empty file (a header line is needed)");
  const auto header = split(lines[0]);
  const auto depth = column(header, "depth_m"), pressure = column(header, "p_dbar");
  const auto t90 = column(header, "t90_degc"), lat = column(header, "lat_deg");
  const auto salinity = column(header, "s_psu"), conductivity = column(header, "conductivity_ms_per_cm");
  auto missing = [&](const std::string& what) {
    return ImportError(name + ":1: the header has no " + what + " column");
  };
  if (!depth && !pressure) throw missing("depth_m or p_dbar");
  if (!t90) throw missing("t90_degc");
  if (!salinity && !conductivity) throw missing("s_psu or conductivity_ms_per_cm");
  if (!lat) throw missing("lat_deg");

  std::vector<CtdSample> samples;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (split(lines[i]) == std::vector<std::string>{""}) continue;  // blank line
    const auto cells = split(lines[i]);
    const std::string where = name + ":" + std::to_string(i + 1) + ": ";
    auto value = [&](std::size_t c) {
      if (c >= cells.size()) throw ImportError(where + "no value for column " + header[c]);
      errno = 0;
      char* end = nullptr;
      const double v = std::strtod(cells[c].c_str(), &end);
      if (cells[c].empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
        throw ImportError(where + header[c] + " '" + cells[c] + "' is not a number");
      return v;
    };
    CtdSample s;
    s.latitude_deg = value(*lat);
    if (!(s.latitude_deg >= -90 && s.latitude_deg <= 90))
      throw ImportError(where + "lat_deg must be within [-90, 90]");
    s.t90_degc = value(*t90);
    if (!(s.t90_degc >= -3 && s.t90_degc <= 40)) throw ImportError(where + "t90_degc must be within [-3, 40]");
    if (depth) {
      s.depth_m = value(*depth);
      if (!(s.depth_m >= 0 && s.depth_m <= 12000)) throw ImportError(where + "depth_m must be within [0, 12000]");
      s.pressure_dbar = unesco_pressure_from_depth(s.depth_m, s.latitude_deg);
    } else {
      s.pressure_dbar = value(*pressure);
      if (!(s.pressure_dbar >= 0 && s.pressure_dbar <= 12000))
        throw ImportError(where + "p_dbar must be within [0, 12000]");
      s.depth_m = unesco_depth_from_pressure(s.pressure_dbar, s.latitude_deg);
    }
    if (salinity) {
      s.salinity_psu = value(*salinity);
    } else {
      const double c = value(*conductivity);
      if (!(c >= 0 && c <= 100)) throw ImportError(where + "conductivity_ms_per_cm must be within [0, 100]");
      s.salinity_psu = practical_salinity(c / kStandardConductivityMsPerCm, t68_from_t90(s.t90_degc), s.pressure_dbar);
    }
    if (!(s.salinity_psu >= 0 && s.salinity_psu <= 42)) throw ImportError(where + "salinity must be within [0, 42]");
    samples.push_back(s);
  }
  if (samples.empty()) throw ImportError(name + ": no samples");
  return samples;
}

double sample_sound_speed(const CtdSample& s, SoundSpeedEquation equation) {
  if (equation == SoundSpeedEquation::kMackenzie)
    return mackenzie_sound_speed(s.t90_degc, s.salinity_psu, s.depth_m);
  return unesco_sound_speed(s.salinity_psu, t68_from_t90(s.t90_degc), s.pressure_dbar);
}

std::vector<SoundSpeedPoint> sound_speed_from_ctd(const std::vector<CtdSample>& cast,
                                                  const CtdProfileOptions& options) {
  // Bin k holds depths in [(k − ½) bin, (k + ½) bin): samples on the bin
  // grid stay at their own depth.
  struct Sum {
    double depth = 0, speed = 0;
    int n = 0;
  };
  std::map<long, Sum> bins;
  for (const auto& s : cast) {
    auto& bin = bins[std::lround(s.depth_m / options.bin_m)];
    bin.depth += s.depth_m;
    bin.speed += sample_sound_speed(s, options.equation);
    ++bin.n;
  }
  std::vector<SoundSpeedPoint> profile;
  for (const auto& [index, sum] : bins) {
    SoundSpeedPoint p;
    p.set_depth_m(sum.depth / sum.n);
    p.set_speed_mps(sum.speed / sum.n);
    profile.push_back(p);
  }
  return profile;
}

}  // namespace acomms::gram
