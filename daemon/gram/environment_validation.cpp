// Environment validation: shared/spec/gram.md §1.5.
#include "gram/environment_validation.h"

#include <cmath>

#include "util/bound_text.h"

namespace acomms::gram {
namespace {

std::string fmt(double v) { return util::format_number(v); }

std::string indexed(const std::string& field, int i) {
  return field + "[" + std::to_string(i) + "]";
}

std::optional<std::string> check_half_space(const Boundary& b, const std::string& name) {
  if (b.kind() != Boundary::HALF_SPACE) return std::nullopt;
  const HalfSpace& h = b.half_space();
  const std::string f = name + ".half_space.";
  if (!(h.speed_mps() > 0) || !std::isfinite(h.speed_mps()))
    return f + "speed_mps = " + fmt(h.speed_mps()) + " must be greater than 0";
  if (!(h.density_ratio() > 0) || !std::isfinite(h.density_ratio()))
    return f + "density_ratio = " + fmt(h.density_ratio()) + " must be greater than 0";
  if (!(h.attenuation_np_per_m() >= 0) || !std::isfinite(h.attenuation_np_per_m()))
    return f + "attenuation_np_per_m = " + fmt(h.attenuation_np_per_m()) + " must be at least 0";
  return std::nullopt;
}

std::optional<std::string> check_profile(const Environment& env) {
  const auto& ssp = env.sound_speed();
  if (ssp.size() < 2)
    return "sound_speed has " + std::to_string(ssp.size()) + " points; at least 2 are needed";
  for (int i = 0; i < ssp.size(); ++i) {
    if (!std::isfinite(ssp[i].depth_m()))
      return indexed("sound_speed", i) + ".depth_m must be a finite number";
    if (!(ssp[i].speed_mps() > 0) || !std::isfinite(ssp[i].speed_mps()))
      return indexed("sound_speed", i) + ".speed_mps = " + fmt(ssp[i].speed_mps()) +
             " must be greater than 0";
    if (i > 0 && !(ssp[i].depth_m() > ssp[i - 1].depth_m()))
      return indexed("sound_speed", i) + ".depth_m = " + fmt(ssp[i].depth_m()) +
             " must be greater than " + indexed("sound_speed", i - 1) +
             ".depth_m = " + fmt(ssp[i - 1].depth_m()) + " (depths strictly increasing)";
  }
  return std::nullopt;
}

std::optional<std::string> check_bathymetry(const Environment& env) {
  const auto& bty = env.bathymetry();
  const double top = env.sound_speed(0).depth_m();
  const double last = env.sound_speed(env.sound_speed_size() - 1).depth_m();
  for (int i = 0; i < bty.size(); ++i) {
    if (!std::isfinite(bty[i].range_m()) || !std::isfinite(bty[i].depth_m()))
      return indexed("bathymetry", i) + " must be finite numbers";
    if (i > 0 && !(bty[i].range_m() > bty[i - 1].range_m()))
      return indexed("bathymetry", i) + ".range_m = " + fmt(bty[i].range_m()) +
             " must be greater than " + indexed("bathymetry", i - 1) + ".range_m = " +
             fmt(bty[i - 1].range_m()) + " (ranges strictly increasing)";
    if (bty[i].depth_m() > last)
      return indexed("bathymetry", i) + ".depth_m = " + fmt(bty[i].depth_m()) +
             " must not be below the last sound_speed depth " + fmt(last);
    if (!(bty[i].depth_m() > top))
      return indexed("bathymetry", i) + ".depth_m = " + fmt(bty[i].depth_m()) +
             " must be below the surface at " + fmt(top);
  }
  return std::nullopt;
}

std::optional<std::string> check_receivers(const Environment& env, const ValidationLimits& limits) {
  const double top = env.sound_speed(0).depth_m();
  const double bottom = deepest_bottom(env);
  if (env.receiver_depth_m_size() == 0) return std::string("receiver_depth_m is empty");
  if (env.receiver_range_m_size() == 0) return std::string("receiver_range_m is empty");
  for (int i = 0; i < env.receiver_depth_m_size(); ++i) {
    const double z = env.receiver_depth_m(i);
    if (!(z >= top && z <= bottom))
      return indexed("receiver_depth_m", i) + " = " + fmt(z) + " must be within the water column [" +
             fmt(top) + ", " + fmt(bottom) + "]";
  }
  for (int i = 0; i < env.receiver_range_m_size(); ++i) {
    const double r = env.receiver_range_m(i);
    if (!(r >= 0) || !std::isfinite(r))
      return indexed("receiver_range_m", i) + " = " + fmt(r) + " must be at least 0";
  }
  const std::size_t nz = env.receiver_depth_m_size(), nr = env.receiver_range_m_size();
  if (env.irregular_receivers() && nz != nr)
    return "irregular receivers need as many receiver_depth_m (" + std::to_string(nz) +
           ") as receiver_range_m (" + std::to_string(nr) + ")";
  const std::size_t count = env.irregular_receivers() ? nr : nz * nr;
  if (count > limits.max_receivers)
    return "receiver grid has " + std::to_string(count) + " points; the limit is " +
           std::to_string(limits.max_receivers);
  return std::nullopt;
}

}  // namespace

double deepest_bottom(const Environment& env) {
  if (env.bathymetry_size() == 0) return env.sound_speed(env.sound_speed_size() - 1).depth_m();
  double deepest = env.bathymetry(0).depth_m();
  for (const auto& p : env.bathymetry()) deepest = std::max(deepest, p.depth_m());
  return deepest;
}

std::optional<std::string> validate_environment(const Environment& env,
                                                const ValidationLimits& limits) {
  if (!(env.frequency_hz() > 0) || !std::isfinite(env.frequency_hz()))
    return "frequency_hz = " + fmt(env.frequency_hz()) + " must be greater than 0";
  if (auto e = check_profile(env)) return e;
  if (auto e = check_half_space(env.surface(), "surface")) return e;
  if (auto e = check_half_space(env.bottom(), "bottom")) return e;
  if (auto e = check_bathymetry(env)) return e;
  const double top = env.sound_speed(0).depth_m();
  const double bottom = deepest_bottom(env);
  if (!(env.source_depth_m() > top && env.source_depth_m() < bottom))
    return "source_depth_m = " + fmt(env.source_depth_m()) + " must be inside the water column (" +
           fmt(top) + ", " + fmt(bottom) + ")";
  if (auto e = check_receivers(env, limits)) return e;
  const double a1 = env.launch_angle_min_deg(), a2 = env.launch_angle_max_deg();
  if (!(a1 > -90.0 && a1 < a2 && a2 < 90.0))
    return "launch angles must satisfy -90 < launch_angle_min_deg (" + fmt(a1) +
           ") < launch_angle_max_deg (" + fmt(a2) + ") < 90";
  if (env.beam_count() > limits.max_beams)
    return "beam_count = " + std::to_string(env.beam_count()) + " exceeds the limit " +
           std::to_string(limits.max_beams);
  if (env.beam_count() == 1)
    return std::string("beam_count = 1: a fan needs at least 2 beams (0 = automatic)");
  if (!(env.step_m() >= 0) || !std::isfinite(env.step_m()))
    return "step_m = " + fmt(env.step_m()) + " must be at least 0 (0 = automatic)";
  if (!(env.box_depth_m() > env.source_depth_m()))
    return "box_depth_m = " + fmt(env.box_depth_m()) + " must be greater than source_depth_m = " +
           fmt(env.source_depth_m());
  if (!(env.box_range_m() > 0) || !std::isfinite(env.box_range_m()))
    return "box_range_m = " + fmt(env.box_range_m()) + " must be greater than 0";
  const auto& att = env.attenuation();
  if (att.kind() == VolumeAttenuation::FRANCOIS_GARRISON) {
    if (!(att.salinity_ppt() >= 0 && att.salinity_ppt() <= 50))
      return "attenuation.salinity_ppt = " + fmt(att.salinity_ppt()) + " must be within [0, 50]";
    if (!(att.temperature_degc() >= -5 && att.temperature_degc() <= 40))
      return "attenuation.temperature_degc = " + fmt(att.temperature_degc()) +
             " must be within [-5, 40]";
    if (!(att.ph() >= 6 && att.ph() <= 9))
      return "attenuation.ph = " + fmt(att.ph()) + " must be within [6, 9]";
    if (!(att.mean_depth_m() >= 0 && att.mean_depth_m() <= 12000))
      return "attenuation.mean_depth_m = " + fmt(att.mean_depth_m()) + " must be within [0, 12000]";
  }
  return std::nullopt;
}

}  // namespace acomms::gram
