// Range-interval beam influence: shared/spec/gram.md §4.8, §4.9, §4.10.
#include "gram/beam_influence.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace acomms::gram {

BeamInfluence::BeamInfluence(const Medium& medium, const ReceiverGrid& receivers, FieldMode mode,
                             BeamShape shape)
    : medium_(medium), receivers_(receivers), mode_(mode), shape_(shape) {}

void BeamInfluence::add(const RayPoint& a, const RayPoint& b, const BeamLaunch& beam,
                        std::vector<std::complex<double>>& pressure,
                        std::vector<double>& intensity) const {
  if (a.r == b.r) return;
  const double r_lo = std::min(a.r, b.r), r_hi = std::max(a.r, b.r);
  const auto& columns = receivers_.columns();
  const double length = std::sqrt((b.r - a.r) * (b.r - a.r) + (b.z - a.z) * (b.z - a.z));
  const double tr = (b.r - a.r) / length, tz = (b.z - a.z) / length;
  const double omega = medium_.omega();
  const double delta_v = medium_.volume_attenuation_np_per_m();
  const double cos0 = beam.abs_cos_angle;
  const double wavelength = beam.source_speed / medium_.frequency();
  const bool coherent = mode_ == COHERENT;
  for (std::size_t j = receivers_.first_column_at_or_after(r_lo);
       j < columns.size() && columns[j].range_m < r_hi; ++j) {
    const ReceiverColumn& col = columns[j];
    if (col.range_m <= 0) continue;  // the source axis: no value in this model
    const double alpha = (col.range_m - a.r) / (b.r - a.r);
    const double z_ray = a.z + alpha * (b.z - a.z);
    const double q = a.q + alpha * (b.q - a.q);
    if (q == 0) continue;
    const double p = a.p + alpha * (b.p - a.p);
    const double c = a.c + alpha * (b.c - a.c);
    const double tau = a.tau + alpha * (b.tau - a.tau);
    const double s = a.s + alpha * (b.s - a.s);
    const double width = std::abs(q) * beam.spacing_rad;
    const double sigma = std::max(width, wavelength);
    const double reach_n = shape_ == HAT ? width : 4.0 * sigma;
    const double reach_z = reach_n / std::abs(tr);
    const double amplitude = std::sqrt(c * cos0 / (beam.source_speed * col.range_m * std::abs(q)));
    const double attenuation = std::exp(-delta_v * s);
    const int caustics = a.caustics + (((q > 0) != (a.q > 0) && a.q != 0) ? 1 : 0);
    const auto& depths = col.depth_m;
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
    auto it = std::lower_bound(depths.begin(), depths.end(), z_ray - reach_z);
    for (auto k = static_cast<std::size_t>(it - depths.begin());
         k < depths.size() && depths[k] <= z_ray + reach_z; ++k) {
      const double dz = depths[k] - z_ray;
      if (coherent) {
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
      }
      const double n = dz * tr;
      double w;
      if (shape_ == HAT) {
        w = 1.0 - std::abs(n) / width;
        if (w <= 0) continue;
      } else {
        if (std::abs(n) > 4.0 * sigma) continue;
        w = width / (std::sqrt(2.0 * std::numbers::pi) * sigma) * std::exp(-n * n / (2 * sigma * sigma));
      }
      const std::size_t out = col.index[k];
      if (coherent) {
        pressure[out] += w * coefficient * phasor;
      } else {
        const double refl = std::norm(a.reflection);
        intensity[out] += amplitude * amplitude * refl * attenuation * attenuation * w *
                          beam.intensity_factor;
      }
    }
  }
}

}  // namespace acomms::gram
