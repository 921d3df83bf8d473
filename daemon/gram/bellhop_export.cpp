// BELLHOP input from an Environment (see bellhop_export.h).
#include "gram/bellhop_export.h"

#include <iomanip>
#include <sstream>

namespace acomms::gram {
namespace {

char boundary_option(const Boundary& b) {
  switch (b.kind()) {
    case Boundary::RIGID: return 'R';
    case Boundary::HALF_SPACE: return 'A';
    default: return 'V';
  }
}

void half_space_line(std::ostream& out, double z, const HalfSpace& h) {
  out << z << " " << h.speed_mps() << " 0.0 " << h.density_ratio() << " " << h.attenuation_np_per_m() << " 0.0 /\n";
}

void vector_line(std::ostream& out, const google::protobuf::RepeatedField<double>& values, double scale) {
  out << values.size() << "\n";
  for (double v : values) out << v * scale << " ";
  out << "/\n";
}

}  // namespace

BellhopInput export_bellhop(const Environment& env) {
  std::ostringstream out;
  out << std::setprecision(17);
  std::string title = env.title().empty() ? "acommsd" : env.title().substr(0, 80);
  for (char& c : title)
    if (c == '\'' || c == '\n' || c == '\r') c = ' ';
  out << "'" << title << "'\n" << env.frequency_hz() << "\n1\n";
  const VolumeAttenuation& att = env.attenuation();
  const char volume = att.kind() == VolumeAttenuation::THORP               ? 'T'
                      : att.kind() == VolumeAttenuation::FRANCOIS_GARRISON ? 'F'
                                                                           : ' ';
  out << "'" << (env.interpolation() == SSP_CUBIC_SPLINE ? 'S' : 'C') << boundary_option(env.surface()) << 'N'
      << volume << "'\n";
  if (volume == 'F')
    out << att.temperature_degc() << " " << att.salinity_ppt() << " " << att.ph() << " " << att.mean_depth_m() << "\n";
  const auto& ssp = env.sound_speed();
  const double surface = ssp[0].depth_m(), bottom = ssp[ssp.size() - 1].depth_m();
  if (env.surface().kind() == Boundary::HALF_SPACE) half_space_line(out, surface, env.surface().half_space());
  out << "0 0.0 " << bottom << "\n";
  for (const auto& p : ssp) out << p.depth_m() << " " << p.speed_mps() << " /\n";
  out << "'" << boundary_option(env.bottom()) << (env.bathymetry_size() > 0 ? "*" : "") << "' 0.0\n";
  if (env.bottom().kind() == Boundary::HALF_SPACE) half_space_line(out, bottom, env.bottom().half_space());
  out << "1\n" << env.source_depth_m() << " /\n";
  vector_line(out, env.receiver_depth_m(), 1.0);
  vector_line(out, env.receiver_range_m(), 1e-3);
  const char mode = env.field_mode() == INCOHERENT ? 'I' : env.field_mode() == SEMI_COHERENT ? 'S' : 'C';
  out << "'" << mode << (env.beam_shape() == GAUSSIAN ? 'B' : 'G') << " R" << (env.irregular_receivers() ? 'I' : 'R')
      << "'\n";
  out << env.beam_count() << "\n";
  out << env.launch_angle_min_deg() << " " << env.launch_angle_max_deg() << " /\n";
  out << env.step_m() << " " << env.box_depth_m() << " " << env.box_range_m() * 1e-3 << "\n";

  BellhopInput input{out.str(), std::nullopt};
  if (env.bathymetry_size() > 0) {
    std::ostringstream bty;
    bty << std::setprecision(17) << "'L'\n" << env.bathymetry_size() << "\n";
    for (const auto& p : env.bathymetry()) bty << p.range_m() * 1e-3 << " " << p.depth_m() << "\n";
    input.bty = bty.str();
  }
  return input;
}

}  // namespace acomms::gram
