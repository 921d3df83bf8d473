// Arrivals and delay spread: shared/spec/gram.md §5.
#include "gram/arrivals.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include "gram/beam_fan.h"
#include "gram/environment_validation.h"
#include "gram/medium.h"
#include "gram/ray.h"
#include "gram/receiver_grid.h"

namespace acomms::gram {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

struct Candidate {
  std::uint32_t beam;
  double weight;     // hat weight w
  double amplitude;  // A w |ΠR| exp(−δ s)
  double delay, launch, arrival;
  std::complex<double> phasor;  // unit phasor of arg(ΠR) − π/2 m_c
  int top, bottom, caustics;
};

void collect(const Medium& medium, const ReceiverGrid& receivers, std::uint32_t beam, double angle,
             double spacing, double c_source, const RayPoint& a, const RayPoint& b,
             std::vector<std::vector<Candidate>>& out) {
  if (a.r == b.r) return;
  const auto& columns = receivers.columns();
  const double length = std::sqrt((b.r - a.r) * (b.r - a.r) + (b.z - a.z) * (b.z - a.z));
  const double tr = (b.r - a.r) / length, tz = (b.z - a.z) / length;
  for (std::size_t j = receivers.first_column_at_or_after(std::min(a.r, b.r));
       j < columns.size() && columns[j].range_m < std::max(a.r, b.r); ++j) {
    const ReceiverColumn& col = columns[j];
    if (col.range_m <= 0) continue;
    const double alpha = (col.range_m - a.r) / (b.r - a.r);
    const double q = a.q + alpha * (b.q - a.q);
    if (q == 0) continue;
    const double z_ray = a.z + alpha * (b.z - a.z);
    const double width = std::abs(q) * spacing;
    const double p = a.p + alpha * (b.p - a.p);
    const double c = a.c + alpha * (b.c - a.c);
    const double tau = a.tau + alpha * (b.tau - a.tau);
    const double s = a.s + alpha * (b.s - a.s);
    const double amplitude = std::sqrt(c * std::abs(std::cos(angle)) / (c_source * col.range_m * std::abs(q)));
    const int caustics = a.caustics + (((q > 0) != (a.q > 0) && a.q != 0) ? 1 : 0);
    for (std::size_t k = 0; k < col.depth_m.size(); ++k) {
      const double dz = col.depth_m[k] - z_ray;
      const double n = dz * tr;
      const double w = 1.0 - std::abs(n) / width;
      if (w <= 0) continue;
      Candidate cand;
      cand.beam = beam;
      cand.weight = w;
      cand.amplitude = amplitude * w * std::abs(a.reflection) *
                       std::exp(-medium.volume_attenuation_np_per_m() * s);
      cand.delay = tau + dz * tz / c + 0.5 * (p / q) * n * n;
      cand.launch = angle * kDegPerRad;
      cand.arrival = std::atan2(tz, tr) * kDegPerRad;
      cand.phasor = std::polar(1.0, std::arg(a.reflection) - 0.5 * std::numbers::pi * caustics);
      cand.top = a.top_bounces;
      cand.bottom = a.bottom_bounces;
      cand.caustics = caustics;
      out[col.index[k]].push_back(cand);
    }
  }
}

std::vector<Arrival> merge(std::vector<Candidate> c, double max_delay_gap, std::size_t keep) {
  std::sort(c.begin(), c.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.top, x.bottom, x.caustics, x.beam) < std::tie(y.top, y.bottom, y.caustics, y.beam);
  });
  std::vector<Arrival> arrivals;
  std::size_t i = 0;
  while (i < c.size()) {
    std::size_t end = i + 1;
    while (end < c.size() && c[end].top == c[i].top && c[end].bottom == c[i].bottom &&
           c[end].caustics == c[i].caustics && c[end].beam == c[end - 1].beam + 1 &&
           std::abs(c[end].delay - c[end - 1].delay) < max_delay_gap)
      ++end;
    Arrival a;
    double weights = 0;
    std::complex<double> phasor{0, 0};
    for (std::size_t k = i; k < end; ++k) {
      a.amplitude += c[k].amplitude;
      weights += c[k].weight;
      a.delay_s += c[k].weight * c[k].delay;
      a.launch_deg += c[k].weight * c[k].launch;
      a.arrival_deg += c[k].weight * c[k].arrival;
      phasor += c[k].weight * c[k].phasor;
    }
    a.delay_s /= weights;
    a.launch_deg /= weights;
    a.arrival_deg /= weights;
    a.phase_deg = std::arg(phasor) * kDegPerRad;
    a.top_bounces = c[i].top;
    a.bottom_bounces = c[i].bottom;
    a.caustics = c[i].caustics;
    arrivals.push_back(a);
    i = end;
  }
  if (arrivals.size() > keep) {
    std::nth_element(arrivals.begin(), arrivals.begin() + static_cast<std::ptrdiff_t>(keep), arrivals.end(),
                     [](const Arrival& x, const Arrival& y) { return x.amplitude > y.amplitude; });
    arrivals.resize(keep);
  }
  std::sort(arrivals.begin(), arrivals.end(),
            [](const Arrival& x, const Arrival& y) { return x.delay_s < y.delay_s; });
  return arrivals;
}

}  // namespace

std::vector<ReceiverArrivals> compute_arrivals(const Environment& env, const ArrivalOptions& options) {
  if (auto error = validate_environment(env)) throw std::invalid_argument(*error);
  const Medium medium(env);
  const ReceiverGrid receivers(env);
  const std::uint32_t beams = beam_count(env);
  const double a1 = env.launch_angle_min_deg() * std::numbers::pi / 180.0;
  const double a2 = env.launch_angle_max_deg() * std::numbers::pi / 180.0;
  const double spacing = (a2 - a1) / (beams - 1);
  const double zs = env.source_depth_m();
  const double c_source = medium.ssp().at(zs, medium.ssp().layer_at(zs, 1.0)).c;

  std::vector<std::vector<Candidate>> candidates(receivers.size());
  for (std::uint32_t m = 0; m < beams; ++m) {
    throw_if_cancelled(options.cancel);
    const double angle = a1 + m * spacing;
    RayTracer ray(medium, angle);
    while (ray.next())
      collect(medium, receivers, m, angle, spacing, c_source, ray.previous(), ray.point(), candidates);
  }
  std::vector<ReceiverArrivals> result(receivers.size());
  for (const auto& column : receivers.columns())
    for (std::size_t k = 0; k < column.index.size(); ++k) {
      auto& r = result[column.index[k]];
      r.range_m = column.range_m;
      r.depth_m = column.depth_m[k];
      r.arrivals = merge(std::move(candidates[column.index[k]]), 0.1 / env.frequency_hz(),
                         options.max_arrivals);
    }
  return result;
}

DelaySpread rms_delay_spread(const std::vector<Arrival>& arrivals, double floor_db) {
  DelaySpread out;
  if (arrivals.empty()) return out;
  double strongest = 0;
  for (const auto& a : arrivals) strongest = std::max(strongest, a.amplitude * a.amplitude);
  const double floor = strongest * std::pow(10.0, -floor_db / 10.0);
  double first = arrivals.front().delay_s;
  for (const auto& a : arrivals) first = std::min(first, a.delay_s);
  double sum = 0, mean = 0;
  for (const auto& a : arrivals) {
    const double intensity = a.amplitude * a.amplitude;
    if (intensity < floor) continue;
    sum += intensity;
    mean += intensity * (a.delay_s - first);  // relative delays: better conditioned
    ++out.arrivals_used;
  }
  mean /= sum;
  double var = 0;
  for (const auto& a : arrivals) {
    const double intensity = a.amplitude * a.amplitude;
    if (intensity < floor) continue;
    var += intensity * (a.delay_s - first - mean) * (a.delay_s - first - mean);
  }
  out.tau_rms_s = std::sqrt(var / sum);
  out.first_delay_s = first;
  return out;
}

}  // namespace acomms::gram
