// .env import: shared/spec/gram.md §7.1, §7.2, §7.4.
#include <cmath>
#include <fstream>
#include <sstream>

#include "gram/bellhop_import.h"

namespace acomms::gram {
namespace {

constexpr double kDbPerNeper = 8.685889638;

char option(const std::string& s, std::size_t i) { return i < s.size() ? s[i] : ' '; }

std::string quoted(char c) { return std::string("'") + c + "'"; }

class EnvParser {
 public:
  EnvParser(std::string_view text, const std::string& name, const SideFileLoader& side)
      : in_(text, name), side_(side) {}

  ImportedEnvironment parse() {
    Environment& env = result_.environment;
    const auto title = in_.next_record(1, 1, "the title");
    env.set_title(title.values[0].text.substr(0, 80));
    env.set_frequency_hz(number_record("the frequency (Hz)"));
    const double media = number_record("NMEDIA");
    if (media != 1)
      in_.fail(line_, "NMEDIA = " + std::to_string(media) + " must be 1 (layered media are not supported)");
    top_options();
    ssp();
    bottom();
    receivers();
    run_type();
    beams();
    return std::move(result_);
  }

 private:
  double number_record(const std::string& what) {
    const auto r = in_.next_record(1, 1, what);
    line_ = r.line;
    if (r.values.empty()) in_.fail(r.line, what + " is missing");
    return in_.number(r.values[0], what, r.line);
  }
  // Values of a record (missing trailing ones keep `defaults`).
  std::vector<double> numbers(std::size_t min, std::vector<double> defaults, const std::string& what) {
    const auto r = in_.next_record(min, defaults.size(), what);
    line_ = r.line;
    for (std::size_t i = 0; i < r.values.size(); ++i) defaults[i] = in_.number(r.values[i], what, r.line);
    return defaults;
  }

  void refuse(const std::string& which, char c, const std::string& why) {
    in_.fail(line_, which + " " + quoted(c) + " is not supported: " + why);
  }

  void top_options() {
    const auto r = in_.next_record(1, 1, "TOPOPT");
    line_ = r.line;
    top_ = r.values[0].text;
    const char interp = option(top_, 0), top = option(top_, 1), volume = option(top_, 3);
    units_ = option(top_, 2);
    if (interp == 'C') result_.environment.set_interpolation(SSP_C_LINEAR);
    else if (interp == 'S') result_.environment.set_interpolation(SSP_CUBIC_SPLINE);
    else if (interp == 'N' || interp == 'P') refuse("TOPOPT(1) SSP interpolation", interp, "only 'C' (c-linear) and 'S' (spline) are implemented");
    else if (interp == 'Q') refuse("TOPOPT(1) SSP interpolation", interp, "range-dependent profiles (.ssp) are not implemented");
    else if (interp == 'A') refuse("TOPOPT(1) SSP interpolation", interp, "the analytic profile is not implemented");
    else refuse("TOPOPT(1) SSP interpolation", interp, "unknown (or 3-D) option");
    if (top != 'V' && top != 'R' && top != 'A') refuse("TOPOPT(2) top boundary", top, "only 'V', 'R' and 'A' are");
    if (std::string("NFMWQL").find(units_) == std::string::npos)
      refuse("TOPOPT(3) attenuation units", units_, "only N F M W Q L are");
    if (volume != ' ' && volume != 'T' && volume != 'F')
      refuse("TOPOPT(4) volume attenuation", volume, "only blank, 'T' (Thorp) and 'F' (Francois-Garrison) are");
    const char altimetry = option(top_, 4);
    if (altimetry == '*' || altimetry == '~') refuse("TOPOPT(5) altimetry", altimetry, "altimetry (.ati) is not implemented");
    if (altimetry != ' ') refuse("TOPOPT(5)", altimetry, "unknown option");
    if (option(top_, 5) != ' ') result_.warnings.push_back("TOPOPT(6) '" + std::string(1, option(top_, 5)) + "' (development option) ignored");
    auto& att = *result_.environment.mutable_attenuation();
    if (volume == 'T') att.set_kind(VolumeAttenuation::THORP);
    if (volume == 'F') {
      const auto v = numbers(4, {0, 0, 0, 0}, "Francois-Garrison T S pH z_bar");
      att.set_kind(VolumeAttenuation::FRANCOIS_GARRISON);
      att.set_temperature_degc(v[0]);
      att.set_salinity_ppt(v[1]);
      att.set_ph(v[2]);
      att.set_mean_depth_m(v[3]);
    }
    if (top == 'A') half_space(*result_.environment.mutable_surface(), "the top half-space");
    else result_.environment.mutable_surface()->set_kind(top == 'V' ? Boundary::VACUUM : Boundary::RIGID);
  }

  void half_space(Boundary& b, const std::string& what) {
    const auto v = numbers(2, {0, 0, 0, 1, 0, 0}, what + " (z cp cs rho ap as)");
    if (v[2] != 0) in_.fail(line_, what + ": shear speed cs = " + std::to_string(v[2]) + " is not supported (must be 0)");
    if (v[5] != 0) in_.fail(line_, what + ": shear attenuation as must be 0");
    if (!(v[1] > 0)) in_.fail(line_, what + ": cp must be greater than 0");
    b.set_kind(Boundary::HALF_SPACE);
    b.mutable_half_space()->set_speed_mps(v[1]);
    b.mutable_half_space()->set_density_ratio(v[3]);
    b.mutable_half_space()->set_attenuation_np_per_m(
        attenuation_np_per_m(units_, v[4], v[1], result_.environment.frequency_hz()));
  }

  void ssp() {
    const auto mesh = numbers(3, {0, 0, 0}, "NMESH SIGMA Z_BOT");
    if (mesh[1] != 0) result_.warnings.push_back("surface roughness SIGMA ignored");
    const double z_bottom = mesh[2];
    std::vector<double> row = {0, 0, 0, 1, 0, 0};
    for (;;) {
      row = numbers(1, row, "a sound speed point (z c)");
      auto* point = result_.environment.add_sound_speed();
      point->set_depth_m(row[0]);
      point->set_speed_mps(row[1]);
      const int n = result_.environment.sound_speed_size();
      if (n > 1 && !(row[0] > result_.environment.sound_speed(n - 2).depth_m()))
        in_.fail(line_, "SSP depth " + std::to_string(row[0]) + " is not greater than the previous one");
      if (row[0] > z_bottom) in_.fail(line_, "SSP depth " + std::to_string(row[0]) + " is below Z_BOT = " + std::to_string(z_bottom));
      if (row[0] == z_bottom) break;
      if (n > 100000) in_.fail(line_, "more than 100000 SSP points");
    }
  }

  void bottom() {
    const auto r = in_.next_record(1, 2, "BOTOPT");
    line_ = r.line;
    const std::string opt = r.values[0].text;
    const char kind = option(opt, 0), bty = option(opt, 1);
    if (r.values.size() > 1 && in_.number(r.values[1], "bottom SIGMA", r.line) != 0)
      result_.warnings.push_back("bottom roughness SIGMA ignored");
    auto& b = *result_.environment.mutable_bottom();
    if (kind == 'A') half_space(b, "the bottom half-space");
    else if (kind == 'V') b.set_kind(Boundary::VACUUM);
    else if (kind == 'R') b.set_kind(Boundary::RIGID);
    else refuse("BOTOPT(1) bottom type", kind, "only 'V', 'R' and 'A' are");
    if (bty == '*' || bty == '~') {
      const auto text = side_ ? side_("bty") : std::nullopt;
      if (!text) in_.fail(r.line, "BOTOPT asks for a bathymetry file (.bty) that cannot be read");
      for (const auto& p : import_bellhop_bty(*text, in_.file_name() + " (.bty)"))
        *result_.environment.add_bathymetry() = p;
      bathymetry_from_file_ = true;
    } else if (bty != ' ') {
      refuse("BOTOPT(2)", bty, "only '*' or '~' (read .bty) are");
    }
  }

  // A vector with BELLHOP's shorthand: N values, or `a b /` for N equally spaced.
  std::vector<double> vector(const std::string& what) {
    const double n = number_record("N" + what);
    if (!(n >= 1 && n <= 1'000'000) || n != std::floor(n))
      in_.fail(line_, "N" + what + " = " + std::to_string(n) + " must be an integer in [1, 1000000]");
    const auto count = static_cast<std::size_t>(n);
    const auto r = in_.next_record(1, count, what + " values");
    line_ = r.line;
    std::vector<double> v;
    for (const auto& value : r.values) v.push_back(in_.number(value, what, r.line));
    if (v.size() == count) return v;
    if (v.size() == 2 && count > 2) {
      std::vector<double> out(count);
      for (std::size_t i = 0; i < count; ++i)
        out[i] = v[0] + (v[1] - v[0]) * static_cast<double>(i) / static_cast<double>(count - 1);
      return out;
    }
    if (v.size() == 1 && count == 1) return v;
    in_.fail(r.line, what + ": " + std::to_string(v.size()) + " values given for N = " + std::to_string(count) + " (give all, or 2 to expand)");
  }

  void receivers() {
    const auto sources = vector("SD (source depths, m)");
    if (sources.size() != 1)
      in_.fail(line_, "NSD = " + std::to_string(sources.size()) + ": one source depth per environment is supported (run each separately)");
    result_.environment.set_source_depth_m(sources[0]);
    for (double z : vector("RD (receiver depths, m)")) result_.environment.add_receiver_depth_m(z);
    for (double r : vector("R (receiver ranges, km)")) result_.environment.add_receiver_range_m(1000.0 * r);
  }

  void run_type() {
    const auto r = in_.next_record(1, 1, "RUNTYPE");
    line_ = r.line;
    const std::string run = r.values[0].text;
    Environment& env = result_.environment;
    switch (option(run, 0)) {
      case 'C': env.set_field_mode(COHERENT); break;
      case 'I': env.set_field_mode(INCOHERENT); break;
      case 'S': env.set_field_mode(SEMI_COHERENT); break;
      case 'A': env.set_field_mode(COHERENT); env.set_arrivals_run(true); break;
      default: refuse("RUNTYPE(1)", option(run, 0), "only C, I, S and A (ASCII arrivals) are");
    }
    const char beam = option(run, 1);
    if (beam == 'G' || beam == '^' || beam == ' ') env.set_beam_shape(HAT);
    else if (beam == 'B') env.set_beam_shape(GAUSSIAN);
    else if (beam == 'g' || beam == 'b') {
      env.set_beam_shape(beam == 'g' ? HAT : GAUSSIAN);
      result_.warnings.push_back(std::string("RUNTYPE(2) '") + beam + "' (ray-centred influence) computed with the Cartesian (range-interval) influence");
    } else refuse("RUNTYPE(2) beam type", beam, "only geometric beams (G ^ g B b) are implemented");
    if (option(run, 2) == '*') refuse("RUNTYPE(3) source beam pattern", '*', "not implemented");
    if (option(run, 3) != 'R' && option(run, 3) != ' ') refuse("RUNTYPE(4) source type", option(run, 3), "only 'R' (point source) is");
    const char grid = option(run, 4);
    if (grid == 'I') env.set_irregular_receivers(true);
    else if (grid != 'R' && grid != ' ') refuse("RUNTYPE(5) receiver grid", grid, "only 'R' and 'I' are");
    if (option(run, 5) != ' ' && option(run, 5) != '2') refuse("RUNTYPE(6)", option(run, 5), "only 2-D runs are");
    if (option(run, 6) == 'S') refuse("RUNTYPE(7) beam shift", 'S', "not implemented");
    if (option(run, 6) != ' ' && option(run, 6) != 'S') refuse("RUNTYPE(7)", option(run, 6), "unknown option");
  }

  void beams() {
    Environment& env = result_.environment;
    const double count = number_record("NBEAMS");
    if (!(count >= 0 && count <= 10'000'000) || count != std::floor(count))
      in_.fail(line_, "NBEAMS must be a non-negative integer");
    env.set_beam_count(static_cast<std::uint32_t>(count));
    const auto angles = numbers(2, {0, 0}, "ALPHA1 ALPHA2");
    env.set_launch_angle_min_deg(angles[0]);
    env.set_launch_angle_max_deg(angles[1]);
    const auto box = numbers(3, {0, 0, 0}, "STEP ZBOX RBOX");
    env.set_step_m(box[0]);
    env.set_box_depth_m(box[1]);
    env.set_box_range_m(1000.0 * box[2]);
    // The bottom is extended flat beyond the file's points (spec §1.4).
    const auto& bty = env.bathymetry();
    if (bathymetry_from_file_ && (bty[0].range_m() > 0 || bty[bty.size() - 1].range_m() < env.box_range_m()))
      result_.warnings.push_back("the bathymetry covers " + std::to_string(bty[0].range_m()) + " to " +
                                 std::to_string(bty[bty.size() - 1].range_m()) +
                                 " m only: its end depths are extended flat to 0 and RBOX");
  }

  ListDirectedReader in_;
  const SideFileLoader& side_;
  ImportedEnvironment result_;
  std::string top_;
  char units_ = 'W';
  bool bathymetry_from_file_ = false;
  std::size_t line_ = 0;
};

}  // namespace

double attenuation_np_per_m(char unit, double a, double c, double f) {
  switch (unit) {
    case 'N': return a;
    case 'M': return a / kDbPerNeper;
    case 'F': return a * (f / 1000.0) / kDbPerNeper;
    case 'W': return a * f / (kDbPerNeper * c);
    case 'Q': return a > 0 ? 2.0 * M_PI * f / (2.0 * c * a) : 0.0;
    case 'L': return a * 2.0 * M_PI * f / c;
    default: throw ImportError(std::string("attenuation unit '") + unit + "' is not known");
  }
}

ImportedEnvironment import_bellhop_env(std::string_view text, const std::string& name,
                                       const SideFileLoader& side) {
  return EnvParser(text, name, side).parse();
}

ImportedEnvironment import_bellhop_env_file(const std::filesystem::path& path) {
  auto read = [](const std::filesystem::path& p) -> std::optional<std::string> {
    std::ifstream in(p, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
  };
  const auto text = read(path);
  if (!text) throw ImportError(path.string() + ": cannot be read");
  SideFileLoader side = [&](const std::string& ext) {
    auto p = path;
    return read(p.replace_extension(ext));
  };
  return import_bellhop_env(*text, path.string(), side);
}

}  // namespace acomms::gram
