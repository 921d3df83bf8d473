// The forecast strategy (see depth_forecast.h).
#include "gram/depth_forecast.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gram/validation_text.h"

namespace acomms::gram {
namespace {

constexpr double kReachSlack_m = 1e-6;  // rounding in w·t

// Linear interpolation over the field's depths, level beyond the ends.
double at_depth(const std::vector<double>& depth, const std::vector<double>& value, double z) {
  if (z <= depth.front()) return value.front();
  if (z >= depth.back()) return value.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(depth.begin(), depth.end(), z) - depth.begin());
  const double t = (z - depth[hi - 1]) / (depth[hi] - depth[hi - 1]);
  return value[hi - 1] + t * (value[hi] - value[hi - 1]);
}

std::size_t nearest(const std::vector<double>& depth, double z) {
  std::size_t best = 0;
  for (std::size_t j = 1; j < depth.size(); ++j)
    if (std::abs(depth[j] - z) < std::abs(depth[best] - z)) best = j;
  return best;
}

class Planner {
 public:
  Planner(const ForecastField& f, double z0, const ForecastOptions& o) : f_(f), z0_(z0), o_(o) {}

  bool shadow(std::size_t k, double z) const {
    return !f_.allowed[k][nearest(f_.depth_m, z)] || at_depth(f_.depth_m, f_.raw[k], z) <= o_.shadow_objective;
  }

  // Local maxima of the steering objective over the allowed depths of
  // column k that are not in shadow.
  std::vector<std::size_t> peaks(std::size_t k) const {
    std::vector<std::size_t> out;
    const auto& s = f_.steer[k];
    const std::size_t n = s.size();
    for (std::size_t j = 0; j < n; ++j) {
      if (!f_.allowed[k][j] || s[j] <= 0 || f_.raw[k][j] <= o_.shadow_objective) continue;
      // At least its neighbours, and above one of them (a plateau's inside
      // is no ridge; an end of the allowed depths has one neighbour).
      const bool has_above = j > 0 && f_.allowed[k][j - 1], has_below = j + 1 < n && f_.allowed[k][j + 1];
      if (has_above && s[j] < s[j - 1]) continue;
      if (has_below && s[j] < s[j + 1]) continue;
      const bool rises = (has_above && s[j] > s[j - 1]) || (has_below && s[j] > s[j + 1]) || (!has_above && !has_below);
      if (rises) out.push_back(j);
    }
    return out;
  }

  // The ridge the vehicle is on, followed to the last column; nullopt when
  // it is on none or the ridge ends (or falls into shadow) within the horizon.
  std::optional<std::vector<std::size_t>> ridge() const {
    if (f_.time_s.size() < 2) return std::nullopt;
    const auto here = peaks(0);
    if (here.empty()) return std::nullopt;
    std::size_t j = here[0];
    for (std::size_t p : here)
      if (std::abs(f_.depth_m[p] - z0_) < std::abs(f_.depth_m[j] - z0_)) j = p;
    const double own = at_depth(f_.depth_m, f_.steer[0], z0_);
    if (own < f_.steer[0][j] - o_.ridge_tolerance || shadow(0, z0_)) return std::nullopt;
    std::vector<std::size_t> track{j};
    for (std::size_t k = 1; k < f_.time_s.size(); ++k) {
      // A ridge is worth staying on while it stays high: within the
      // tolerance of the best the vehicle could reach by then.
      const double reach = o_.vertical_speed_mps * (f_.time_s[k] - f_.time_s[k - 1]) + kReachSlack_m;
      const double from = k == 1 ? z0_ : f_.depth_m[track.back()];
      std::optional<std::size_t> next;
      for (std::size_t p : peaks(k)) {
        const double d = std::abs(f_.depth_m[p] - from);
        if (d <= reach && (!next || d < std::abs(f_.depth_m[*next] - from))) next = p;
      }
      if (!next || f_.steer[k][*next] < best_reachable(k) - o_.ridge_tolerance) return std::nullopt;
      track.push_back(*next);
    }
    return track;
  }

  // The largest steering objective of column k within reach of z0 by t_k.
  double best_reachable(std::size_t k) const {
    const double reach = o_.vertical_speed_mps * f_.time_s[k] + kReachSlack_m;
    double best = 0;
    for (std::size_t j = 0; j < f_.depth_m.size(); ++j)
      if (f_.allowed[k][j] && std::abs(f_.depth_m[j] - z0_) <= reach) best = std::max(best, f_.steer[k][j]);
    return best;
  }

  // True when the straight path from (0, z0) to (t_k, z) enters a shadow
  // after having been out of one.
  bool crosses_shadow(std::size_t k, double z) const {
    bool lit = false;
    for (std::size_t i = 0; i <= k; ++i) {
      const double zi = z0_ + (z - z0_) * f_.time_s[i] / f_.time_s[k];
      const bool dark = shadow(i, zi);
      if (dark && lit) return true;
      lit = lit || !dark;
    }
    return false;
  }

  ForecastDecision optimum() const {
    struct Candidate {
      std::size_t k, j;
      double value, rate;
    };
    std::vector<Candidate> ok;
    for (std::size_t k = 1; k < f_.time_s.size(); ++k) {
      const double reach = o_.vertical_speed_mps * f_.time_s[k] + kReachSlack_m;
      for (std::size_t j = 0; j < f_.depth_m.size(); ++j) {
        const double z = f_.depth_m[j];
        if (!f_.allowed[k][j] || f_.steer[k][j] <= 0 || f_.raw[k][j] <= o_.shadow_objective) continue;
        if (std::abs(z - z0_) > reach || crosses_shadow(k, z)) continue;
        ok.push_back({k, j, f_.steer[k][j], std::abs(z - z0_) / f_.time_s[k]});
      }
    }
    ForecastDecision d;
    d.target_depth_m = z0_;
    if (ok.empty()) return d;  // hold
    double best = 0;
    for (const Candidate& c : ok) best = std::max(best, c.value);
    // The earliest column holding a near-best point, and in it the least
    // pitch (ok is in order of column, then depth: ties go shallowest).
    const Candidate* pick = nullptr;
    for (const Candidate& c : ok) {
      if (c.value < best * (1 - o_.optimum_tolerance)) continue;
      if (pick && c.k != pick->k) break;
      if (!pick || c.rate < pick->rate) pick = &c;
    }
    d.choice = ForecastChoice::kOptimum;
    d.target_depth_m = f_.depth_m[pick->j];
    d.target_time_s = f_.time_s[pick->k];
    d.target_objective = pick->value;
    d.vertical_rate_mps = pick->rate;
    return d;
  }

 private:
  const ForecastField& f_;
  double z0_;
  const ForecastOptions& o_;
};

}  // namespace

const char* forecast_choice_name(ForecastChoice choice) {
  switch (choice) {
    case ForecastChoice::kRidge: return "ridge";
    case ForecastChoice::kOptimum: return "optimum";
    case ForecastChoice::kHold: return "hold";
  }
  return "hold";
}

double ForecastDecision::depth_after(double z0, double dt) const {
  if (choice == ForecastChoice::kHold || dt <= 0) return z0;
  if (choice == ForecastChoice::kOptimum) {
    if (dt >= target_time_s) return target_depth_m;
    return z0 + (target_depth_m - z0) * dt / target_time_s;
  }
  // Along the ridge: from (0, z0) through its depth in each later column.
  double t_prev = 0, z_prev = z0;
  for (std::size_t k = 1; k < ridge_time_s.size(); ++k) {
    if (dt <= ridge_time_s[k]) return z_prev + (ridge_depth_m[k] - z_prev) * (dt - t_prev) / (ridge_time_s[k] - t_prev);
    t_prev = ridge_time_s[k];
    z_prev = ridge_depth_m[k];
  }
  return z_prev;
}

std::optional<std::string> validate_forecast_field(const ForecastField& f) {
  if (f.depth_m.empty()) return "the forecast field has no depths";
  for (std::size_t j = 1; j < f.depth_m.size(); ++j)
    if (!(f.depth_m[j] > f.depth_m[j - 1])) return "the forecast field's depths must be strictly increasing";
  if (f.time_s.empty() || f.time_s[0] != 0) return "the forecast field's first column must be at time 0";
  for (std::size_t k = 1; k < f.time_s.size(); ++k)
    if (!(f.time_s[k] > f.time_s[k - 1])) return "the forecast field's times must be strictly increasing";
  const std::size_t nk = f.time_s.size(), nj = f.depth_m.size();
  if (f.steer.size() != nk || f.raw.size() != nk || f.allowed.size() != nk)
    return "the forecast field needs one steer, raw and allowed column per time";
  for (std::size_t k = 0; k < nk; ++k) {
    if (f.steer[k].size() != nj || f.raw[k].size() != nj || f.allowed[k].size() != nj)
      return "forecast column " + std::to_string(k) + " does not have one value per depth";
    for (std::size_t j = 0; j < nj; ++j)
      if (!std::isfinite(f.steer[k][j]) || !std::isfinite(f.raw[k][j]))
        return "forecast column " + std::to_string(k) + " holds a value that is not finite";
  }
  return std::nullopt;
}

std::optional<std::string> validate_forecast_options(const ForecastOptions& o) {
  if (auto e = require_greater("vertical_speed_mps", o.vertical_speed_mps, 0.0)) return e;
  if (!(o.ridge_tolerance >= 0 && o.ridge_tolerance <= 1)) return "ridge_tolerance must be in [0, 1]";
  if (!(o.optimum_tolerance >= 0 && o.optimum_tolerance <= 1)) return "optimum_tolerance must be in [0, 1]";
  if (!(o.shadow_objective >= 0 && o.shadow_objective < 1)) return "shadow_objective must be in [0, 1)";
  return std::nullopt;
}

std::optional<std::string> validate_depth_forecast_request(const DepthForecastRequest& r, double horizon_s) {
  if (!(r.forecast_horizon_s >= horizon_s) || !std::isfinite(r.forecast_horizon_s))
    return "forecast_horizon_s = " + format_number(r.forecast_horizon_s) + " must be at least horizon_s = " +
           format_number(horizon_s) + " (one forecast column every horizon_s)";
  if (r.forecast_horizon_s / horizon_s > kMaxForecastColumns)
    return "forecast_horizon_s = " + format_number(r.forecast_horizon_s) + " must be at most " +
           format_number(kMaxForecastColumns) + " times horizon_s = " + format_number(horizon_s) +
           " (one forecast column every horizon_s)";
  if (r.leg_end_range_m && !(*r.leg_end_range_m >= 0 && std::isfinite(*r.leg_end_range_m)))
    return "leg_end_range_m must be finite and at least 0";
  if (auto e = require_at_least("current_depth_m", r.current_depth_m, 0.0)) return e;
  if (auto e = require_at_least("caustic_uncertainty_m", r.caustic_uncertainty_m, 0.0)) return e;
  return validate_forecast_options(r.options);
}

ForecastDecision forecast_depth(const ForecastField& field, double z0, const ForecastOptions& options) {
  if (auto e = validate_forecast_field(field)) throw std::invalid_argument(*e);
  if (auto e = validate_forecast_options(options)) throw std::invalid_argument(*e);
  if (!std::isfinite(z0)) throw std::invalid_argument("current_depth_m must be finite");
  const Planner planner(field, z0, options);
  if (auto track = planner.ridge()) {
    ForecastDecision d;
    d.choice = ForecastChoice::kRidge;
    for (std::size_t j : *track) d.ridge_depth_m.push_back(field.depth_m[j]);
    d.ridge_time_s = field.time_s;
    d.target_depth_m = d.ridge_depth_m[1];
    d.target_time_s = field.time_s[1];
    d.target_objective = field.steer[1][(*track)[1]];
    d.vertical_rate_mps = std::abs(d.target_depth_m - z0) / d.target_time_s;
    return d;
  }
  return planner.optimum();
}

}  // namespace acomms::gram
