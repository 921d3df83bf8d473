// Ray and dynamic ray tracing: shared/spec/gram.md §4.1–§4.6.
#include "gram/ray.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gram/reflection.h"

namespace acomms::gram {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kMaxSteps = 2'000'000;    // guard against loops
constexpr double kAmplitudeFloor = 1e-6;        // |ΠR| exp(−δ s) below this: stop

enum class Target { kNone, kNode, kSurface, kBottom, kSegmentEnd };

// Smallest positive arc length h with gap − rate h − ½ curvature h² = 0:
// when a quantity `gap` away, approached at `rate` per metre of ray with
// `curvature`, is reached; +∞ if never (it turns away first).
[[gnu::always_inline]] inline double arc_to_offset(double gap, double rate, double curvature) {
  const double a = 0.5 * curvature;
  if (rate > 0) {
    // Heading for it (the common case: the next node ahead). The near root
    // is (gap/rate) · 2/(1 + √(1 + 4u)), u = a gap/rate²; for |u| ≤ 1e-3 the
    // series 1 − u + 2u² − 5u³ gives it to 14u⁴ ≤ 1.4e-11 relative, without
    // the square root that would sit on every step's critical path.
    const double inv_rate = 1.0 / rate;
    const double near = gap * inv_rate;
    const double u = a * near * inv_rate;
    if (std::abs(u) <= 1e-3 && near > 2e-9) return near * (1.0 - u * (1.0 - u * (2.0 - 5.0 * u)));
  }
  if (std::abs(a) * gap < 1e-12 * std::max(rate * rate, 1e-300)) {
    return rate > 0 ? gap / rate : kInf;
  }
  const double disc = rate * rate + 4.0 * a * gap;
  if (disc < 0) return kInf;
  const double root = std::sqrt(disc);
  // Roots of a h² + rate h − gap = 0, in a cancellation-free form.
  const double q = -0.5 * (rate + std::copysign(root, rate));
  double best = kInf;
  for (double h : {q / a, q != 0 ? -gap / q : kInf})
    if (h > 1e-9 && h < best) best = h;
  return best;
}

}  // namespace

RayTracer::RayTracer(const Medium& medium, double angle) : medium_(medium) {
  const double zs = medium.source_depth();
  layer_ = medium.ssp().layer_at(zs, std::sin(angle));
  const double c = medium.ssp().at(zs, layer_).c;
  RayPoint& start = points_[current_];
  start.z = zs;
  start.c = c;
  start.xi = std::cos(angle) / c;
  start.zeta = std::sin(angle) / c;
  start.p = 1.0 / c;
  segment_ = medium.segment_at(0.0);
  here_ = medium.ssp().at(zs, layer_);
  update_fade();
}

void RayTracer::update_fade() {
  // |ΠR| exp(−δ s) < floor  ⇔  s > ln(|ΠR| / floor) / δ: one log per
  // reflection instead of an exp per step.
  // |ΠR| ≤ 1: no overflow to guard against, so no hypot.
  const double magnitude = std::sqrt(std::norm(point().reflection));
  const double delta = medium_.volume_attenuation_np_per_m();
  if (magnitude < kAmplitudeFloor) faded_at_s_ = -kInf;
  else if (delta > 0) faded_at_s_ = std::log(magnitude / kAmplitudeFloor) / delta;
  else faded_at_s_ = kInf;
}

[[gnu::always_inline]] inline void RayTracer::integrate(const RayPoint& y,
                                                        const SoundSpeedProfile::Value& at_y, double h,
                                                        RayPoint& out) const {
  // Midpoint (RK2) step of (r, z, ξ, ζ, τ, q, p); c_r = 0 (range-independent
  // SSP), so ξ is constant within the step. `at_y` is c and its derivatives
  // at y, which every try shares. The slopes: dr = cξ, dz = cζ,
  // dζ = −c_z/c², dτ = 1/c, dq = c p, dp = −c_zz (cξ)²/c² q = −c_zz ξ² q.
  const double half = 0.5 * h;
  const double xi2 = y.xi * y.xi;
  const double inv_c1 = 1.0 / at_y.c;
  const double mid_z = y.z + half * at_y.c * y.zeta;
  const double mid_zeta = y.zeta - half * at_y.cz * inv_c1 * inv_c1;
  const double mid_q = y.q + half * at_y.c * y.p;
  const double mid_p = y.p - half * at_y.czz * xi2 * y.q;
  SoundSpeedProfile::Value v;
  double inv_c2;
  if (medium_.ssp().lands_on_nodes()) {
    // c-linear: c(mid) = c (1 + δ), δ = c_z (mid_z − z)/c = ½ h c_z ζ, known
    // as soon as h is: 1/c(mid) need not wait for the midpoint's depth.
    const double stretch = 1.0 + half * at_y.cz * y.zeta;
    v = {at_y.c * stretch, at_y.cz, 0.0};
    inv_c2 = inv_c1 / stretch;
  } else {
    v = medium_.ssp().at(mid_z, layer_);
    inv_c2 = 1.0 / v.c;
  }
  // Field by field: the bounce counts, caustics and ΠR do not change within
  // a step (next() copies them once), and a whole-struct copy here would
  // be redone on every secant try.
  out.r = y.r + h * v.c * y.xi;
  out.z = y.z + h * v.c * mid_zeta;
  out.xi = y.xi;
  out.zeta = y.zeta - h * v.cz * inv_c2 * inv_c2;
  out.tau = y.tau + h * inv_c2;
  out.q = y.q + h * v.c * mid_p;
  out.p = y.p - h * v.czz * xi2 * mid_q;
  out.s = y.s + h;
}

double RayTracer::bottom_offset(const RayPoint& at) const {
  return at.z - medium_.bottom_segments()[segment_].depth_at(at.r);
}

// Inline: half the steps of a c-linear run end on a node.
[[gnu::always_inline]] inline void RayTracer::land_on_node(std::size_t node) {
  // c_z jumps at a c-linear node: p jumps, q is continuous (spec §4.4).
  RayPoint& y = points_[current_];
  const auto& ssp = medium_.ssp();
  const double cz_before = ssp.at(y.z, layer_).cz;
  layer_ = y.zeta > 0 ? node : node - 1;
  const double cz_after = ssp.at(y.z, layer_).cz;
  const double cos_t = y.c * y.xi, sin_t = y.c * y.zeta;
  if (std::abs(sin_t) < 1e-12) return;  // turning exactly on the node: no crossing
  y.p -= y.q * (cz_after - cz_before) * cos_t * cos_t / (y.c * y.c * sin_t);
}

bool RayTracer::next() {
  if (ended_) return false;
  const auto& ssp = medium_.ssp();
  const RayPoint& y = points_[current_];
  RayPoint& out = points_[current_ ^ 1];  // the slot of the point before y
  const SoundSpeedProfile::Value at_y = here_;
  const double c = at_y.c;
  const double tr = c * y.xi, tz = c * y.zeta;  // unit tangent
  // The first boundary ahead along the (curving) ray decides the step. Depth
  // crossings are predicted with the ray's curvature d²z/ds² = −(c_z/c) cos²θ,
  // so a ray that turns before a node is not sent to it.
  const double kappa = -at_y.cz * c * y.xi * y.xi;  // = −(c_z/c) t_r², without a division
  double h = medium_.max_step();
  Target target = Target::kNone;
  std::size_t node = 0;
  auto consider = [&](double distance, Target t) {
    if (distance > 1e-9 && distance <= h) { h = distance; target = t; }
  };
  // A depth target out of reach within h, whatever the curvature, needs no
  // root: the quadratic model moves at most |t_z| h + ½|κ| h² ≤ reach.
  const double reach = h * (1.0 + 0.5 * std::abs(kappa) * h);
  if (y.z - ssp.top() <= reach) consider(arc_to_offset(y.z - ssp.top(), -tz, -kappa), Target::kSurface);
  if (ssp.lands_on_nodes()) {
    // A node behind the ray matters only if the ray can turn within the step.
    const bool can_rise = tz < 0 || tz + kappa * h < 0;
    const bool can_sink = tz > 0 || tz + kappa * h > 0;
    const double gap_up = y.z - ssp.node(layer_);
    const double gap_down = layer_ + 1 < ssp.layer_count() ? ssp.node(layer_ + 1) - y.z : kInf;
    const double up = layer_ > 0 && can_rise && gap_up <= reach ? arc_to_offset(gap_up, -tz, -kappa) : kInf;
    const double down = can_sink && gap_down <= reach ? arc_to_offset(gap_down, tz, kappa) : kInf;
    node = up < down ? layer_ : layer_ + 1;
    consider(std::min(up, down), Target::kNode);
  }
  const BottomSegment& seg = medium_.bottom_segments()[segment_];
  const double bottom_gap = -bottom_offset(y);
  if (bottom_gap <= reach * (1.0 + std::abs(seg.slope)))
    consider(arc_to_offset(bottom_gap, tz - seg.slope * tr, kappa), Target::kBottom);
  if (tr > 0 && std::isfinite(seg.r1)) consider((seg.r1 - y.r) / tr, Target::kSegmentEnd);
  if (tr < 0 && std::isfinite(seg.r0)) consider((seg.r0 - y.r) / tr, Target::kSegmentEnd);

  // Signed distance still to go to the target (negative: overshot). An
  // overshoot is corrected by the secant ratio (≤ 3 tries, spec §4.3); a ray
  // that falls short (it turned) is not moved onto the target.
  const double approach = target == Target::kNode || target == Target::kSurface
                              ? (tz + kappa * h > 0 ? 1.0 : -1.0)
                              : 1.0;
  auto offset = [&](const RayPoint& at) {
    switch (target) {
      case Target::kSurface: return (ssp.top() - at.z) * approach;
      case Target::kNode: return (ssp.node(node) - at.z) * approach;
      case Target::kBottom: return -bottom_offset(at);
      case Target::kSegmentEnd: return ((tr > 0 ? seg.r1 : seg.r0) - at.r) * (tr > 0 ? 1.0 : -1.0);
      default: return kInf;
    }
  };
  constexpr double kLandingTolerance = 1e-4;  // m
  integrate(y, at_y, h, out);
  for (int tries = 0; tries < 3 && target != Target::kNone && offset(out) < -kLandingTolerance; ++tries) {
    const double before = offset(y), after = offset(out);
    h *= before / (before - after);
    integrate(y, at_y, h, out);
  }
  if (target != Target::kNone && std::abs(offset(out)) > kLandingTolerance) target = Target::kNone;
  out.reflection = y.reflection;
  out.caustics = y.caustics;
  out.top_bounces = y.top_bounces;
  out.bottom_bounces = y.bottom_bounces;
  switch (target) {
    case Target::kSurface: out.z = ssp.top(); break;
    case Target::kNode: out.z = ssp.node(node); break;
    case Target::kBottom: out.z = seg.depth_at(out.r); break;
    case Target::kSegmentEnd: out.r = tr > 0 ? seg.r1 : seg.r0; break;
    default: break;
  }
  if (out.z < ssp.top()) out.z = ssp.top();  // never above the surface
  // Renormalise the slowness vector to 1/c at the new point.
  const std::size_t layer_before_events = layer_;
  const auto v = ssp.at(out.z, layer_);
  // scale = 1/√x with x = (ξ² + ζ²) c², which an RK2 step leaves within
  // ~1e-9 of 1: there the series 1 − e/2 + 3e²/8 (e = x − 1, error below
  // 5e³/16 < 1e-18) replaces a square root and a division, which sit on the
  // critical path of every step.
  const double x = (out.xi * out.xi + out.zeta * out.zeta) * (v.c * v.c);
  const double e = x - 1.0;
  const double scale = std::abs(e) < 1e-6 ? 1.0 - e * (0.5 - 0.375 * e) : 1.0 / std::sqrt(x);
  out.xi *= scale;
  out.zeta *= scale;
  out.c = v.c;
  if ((out.q > 0) != (y.q > 0) && y.q != 0) ++out.caustics;
  else if (out.q == 0) ++out.caustics;
  current_ ^= 1;  // out is now point(), y previous()
  // A spline profile is not landed on at nodes: follow the layer here.
  if (!ssp.lands_on_nodes() &&
      (out.z < ssp.node(layer_) || out.z > ssp.node(layer_ + 1)))
    layer_ = ssp.layer_at(out.z, out.zeta);

  switch (target) {
    case Target::kNode: land_on_node(node); break;
    case Target::kSurface: reflect(true); break;
    case Target::kBottom: reflect(false); break;
    case Target::kSegmentEnd: segment_ = tr > 0 ? segment_ + 1 : segment_ - 1; break;
    default: break;
  }
  // c and its derivatives at the new point, for the next step (the layer,
  // hence c_z, may have changed at a node or a reflection).
  here_ = layer_ == layer_before_events ? v : ssp.at(out.z, layer_);
  if (out.r > medium_.box_range() || out.r < 0 || out.z > medium_.box_depth() ||
      out.s > faded_at_s_ || ++steps_ >= kMaxSteps)
    ended_ = true;
  return true;
}

void RayTracer::reflect(bool top) {
  RayPoint& y = points_[current_];
  const auto& ssp = medium_.ssp();
  // Boundary tangent along increasing range and ν = (−τ_z, τ_r) (spec §4.4, §4.5).
  double taur = 1.0, tauz = 0.0;
  if (!top) {
    const double slope = medium_.bottom_segments()[segment_].slope;
    const double n = std::sqrt(1.0 + slope * slope);
    taur = 1.0 / n;
    tauz = slope / n;
  }
  const double nur = -tauz, nuz = taur;
  const double tr = y.c * y.xi, tz = y.c * y.zeta;
  const double t_nu = tr * nur + tz * nuz;
  const double grazing = std::asin(std::min(1.0, std::abs(t_nu)));
  // p: the gradient term of a mirror medium, Δ∇c = −2 (∇c·ν) ν, incident direction.
  const double cz = ssp.at(y.z, layer_).cz;
  const double grad_nu = cz * nuz;
  const double dgr = -2.0 * grad_nu * nur, dgz = -2.0 * grad_nu * nuz;
  const double dg_n = dgr * (-tz) + dgz * tr;  // Δ∇c · n̂, n̂ = (−sin θ, cos θ)
  const double t_tau = tr * taur + tz * tauz;
  if (t_nu != 0) y.p -= y.q * dg_n * t_tau / (t_nu * y.c * y.c);
  // Direction: mirror about the boundary.
  const double nr = tr - 2.0 * t_nu * nur, nz = tz - 2.0 * t_nu * nuz;
  y.xi = nr / y.c;
  y.zeta = nz / y.c;
  const Boundary& b = top ? medium_.surface() : medium_.bottom();
  y.reflection *= reflection_coefficient(b, grazing, y.c, medium_.omega());
  if (top) ++y.top_bounces;
  else ++y.bottom_bounces;
  update_fade();
  layer_ = ssp.layer_at(y.z, y.zeta);
}

}  // namespace acomms::gram
