// Range-interval beam influence: shared/spec/gram.md §4.8, §4.9, §4.10.
#include "gram/beam_influence.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace acomms::gram {

BeamInfluence::BeamInfluence(const Medium& medium, const ReceiverGrid& receivers, FieldMode mode,
                             BeamShape shape)
    : medium_(medium), receivers_(receivers), mode_(mode), shape_(shape) {}

void BeamInfluence::add_columns(std::size_t j, double r_hi, const RayPoint& a, const RayPoint& b,
                                const BeamLaunch& beam, std::span<std::complex<double>> pressure,
                                std::span<double> intensity) const {
  const auto& columns = receivers_.columns();
  const double length = std::sqrt((b.r - a.r) * (b.r - a.r) + (b.z - a.z) * (b.z - a.z));
  const double tr = (b.r - a.r) / length, tz = (b.z - a.z) / length;
  const double inv_dr = 1.0 / (b.r - a.r);
  const double inv_abs_tr = length / std::abs(b.r - a.r);
  const double omega = medium_.omega();
  const double delta_v = medium_.volume_attenuation_np_per_m();
  const double cos0 = beam.abs_cos_angle;
  const double wavelength = beam.source_speed / medium_.frequency();
  const bool coherent = mode_ == COHERENT;
  const bool hat = shape_ == HAT;
  // Incoherent: A² |ΠR|² exp(−2δs) w, with A² = c cos θ0 / (c_s r |q|).
  const double intensity_scale = std::norm(a.reflection) * cos0 / beam.source_speed * beam.intensity_factor;
  for (; j < columns.size() && columns[j].range_m < r_hi; ++j) {
    const ReceiverColumn& col = columns[j];
    if (col.range_m <= 0) continue;  // the source axis: no value in this model
    const double alpha = (col.range_m - a.r) * inv_dr;
    const double z_ray = a.z + alpha * (b.z - a.z);
    const double q = a.q + alpha * (b.q - a.q);
    if (q == 0) continue;
    const double abs_q = std::abs(q);
    const double c = a.c + alpha * (b.c - a.c);
    const double s = a.s + alpha * (b.s - a.s);
    const double width = abs_q * beam.spacing_rad;
    const double sigma = hat ? width : std::max(width, wavelength);
    const double reach_n = hat ? width : 4.0 * sigma;
    const double reach_z = reach_n * inv_abs_tr;
    const auto& depths = receivers_.depths(col);
    std::size_t k = receivers_.first_depth_at_or_after(col, z_ray - reach_z);
    if (k >= depths.size() || depths[k] > z_ray + reach_z) continue;  // the beam misses every depth
    // Per-receiver weight w(n): hat 1 − |n|/W, Gaussian W/(√(2π) σ) exp(−n²/2σ²).
    const double inv_width = 1.0 / width;
    double gauss_scale = 0, gauss_exponent = 0;  // hat beams need neither division
    if (!hat) {
      gauss_scale = width / (std::sqrt(2.0 * std::numbers::pi) * sigma);
      gauss_exponent = -1.0 / (2 * sigma * sigma);
    }
    auto weight = [&](double n) {
      return hat ? 1.0 - std::abs(n) * inv_width
                 : (std::abs(n) > reach_n ? 0.0 : gauss_scale * std::exp(n * n * gauss_exponent));
    };
    if (!coherent) {
      const double attenuation2 = delta_v > 0 ? std::exp(-2.0 * delta_v * s) : 1.0;
      const double scale = c * intensity_scale / (col.range_m * abs_q) * attenuation2;
      for (; k < depths.size() && depths[k] <= z_ray + reach_z; ++k) {
        const double w = weight((depths[k] - z_ray) * tr);
        if (w > 0) intensity[col.first_slot + k] += scale * w;
      }
      continue;
    }
    const double p = a.p + alpha * (b.p - a.p);
    const double tau = a.tau + alpha * (b.tau - a.tau);
    const double amplitude = std::sqrt(c * cos0 / (beam.source_speed * col.range_m * abs_q));
    const double attenuation = delta_v > 0 ? std::exp(-delta_v * s) : 1.0;
    const int caustics = a.caustics + (((q > 0) != (a.q > 0) && a.q != 0) ? 1 : 0);
    const double pq = p / q;
    auto phase_at = [&](double dz) {
      const double n = dz * tr;
      return omega * (tau + dz * tz / c + 0.5 * pq * n * n) - 0.5 * std::numbers::pi * caustics;
    };
    // On evenly spaced depths the phase is quadratic in the index: advance
    // the phasor by complex rotations instead of a sincos per receiver.
    const double spacing = col.uniform_spacing;
    std::complex<double> phasor, rotation, step_rotation;
    bool first = true;
    const std::complex<double> coefficient = amplitude * attenuation * a.reflection;
    for (; k < depths.size() && depths[k] <= z_ray + reach_z; ++k) {
      const double dz = depths[k] - z_ray;
      if (first || spacing == 0) {
        phasor = std::polar(1.0, phase_at(dz));
        if (spacing > 0) {
          const double curvature = pq * tr * tr;
          rotation = std::polar(1.0, omega * (spacing * tz / c + curvature * (dz * spacing + 0.5 * spacing * spacing)));
          step_rotation = std::polar(1.0, omega * curvature * spacing * spacing);
        }
        first = false;
      } else {
        phasor *= rotation;
        rotation *= step_rotation;
      }
      const double w = weight(dz * tr);
      if (w > 0) pressure[col.first_slot + k] += w * coefficient * phasor;
    }
  }
}

}  // namespace acomms::gram
