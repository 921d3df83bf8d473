// The forecast strategy: a path planner over the forecast field (see
// depth_forecast.h).
#include "gram/depth_forecast.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "gram/validation_text.h"

namespace acomms::gram {
namespace {

constexpr double kMaxPlanStep_m = 10;      // the plan's depth grid is at least this fine
constexpr double kMaxStepsPerReach = 16;   // and no finer than w·Δt / this (bounds the work)
constexpr double kMaxPlanNodes = 4000;     // nor finer than the field's depths / this
constexpr double kMinPlanStep_m = 1e-3;    // nor than a millimetre (a field a few metres deep)
constexpr double kMaxMovesPerStep = 127;   // grid steps between layers (a move fits an int8)
constexpr double kMaxTerminalSteps = 480;  // nor longer past the horizon than this many columns
constexpr double kMaxTerminal_s = 86400;   // a day: bounds the plan's length
constexpr double kMaxVerticalSpeed_mps = 10;  // no vehicle dives faster; bounds w·Δt / step
constexpr double kNever = -std::numeric_limits<double>::infinity();
// The score of a cell the limits forbid, on the way back into the allowed
// depths: below any allowed cell's, so the way back is the quickest (and
// lower the further out, to −2).
constexpr double kOutside = -1;
constexpr int kNoAllowed = std::numeric_limits<int>::max();

// Linear interpolation over the field's depths, level beyond the ends.
double at_depth(const std::vector<double>& depth, const std::vector<double>& value, double z) {
  if (z <= depth.front()) return value.front();
  if (z >= depth.back()) return value.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(depth.begin(), depth.end(), z) - depth.begin());
  const double t = (z - depth[hi - 1]) / (depth[hi] - depth[hi - 1]);
  return value[hi - 1] + t * (value[hi] - value[hi - 1]);
}

// Whether depth z is allowed in a column: on a field depth, that depth's
// flag; between two, both (the limits may lie anywhere between them, so a
// depth between an allowed and a forbidden one may be past a limit).
bool allowed_at(const std::vector<double>& depth, const std::vector<bool>& allowed, double z) {
  constexpr double kOn = 1e-6;
  if (z < depth.front() - kOn || z > depth.back() + kOn) return false;
  const auto hi = static_cast<std::size_t>(std::upper_bound(depth.begin(), depth.end(), z) - depth.begin());
  if (hi == 0) return allowed.front();
  if (hi == depth.size()) return allowed.back();
  if (z - depth[hi - 1] <= kOn) return allowed[hi - 1];
  if (depth[hi] - z <= kOn) return allowed[hi];
  return allowed[hi - 1] && allowed[hi];
}

// A double (finite or not) as a count in [lo, hi]: clamped before the cast.
long to_count(double x, double lo, double hi) {
  return static_cast<long>(std::isnan(x) ? lo : std::clamp(x, lo, hi));
}

// The plan over layers: layer l is the time t_l (the field's columns, then
// `extra` copies of the last column's spacing with its field frozen), node
// i the depth zs + (i − start) h, over the field's depths only.
class Planner {
 public:
  Planner(const ForecastField& f, double z0, const ForecastOptions& o) : f_(f), z0_(z0), o_(o) {
    const std::size_t n = f_.time_s.size();
    const double top = f_.depth_m.front(), span = f_.depth_m.back() - top;
    // A vehicle outside the field's depths plans from the field's nearest
    // end: the model says nothing beyond them, and the grid (the work)
    // stays the field's whatever depth a client reports.
    zs_ = std::clamp(z0_, top, f_.depth_m.back());
    double min_dt = INFINITY;
    for (std::size_t k = 0; k + 1 < n; ++k) {
      dt_.push_back(f_.time_s[k + 1] - f_.time_s[k]);
      min_dt = std::min(min_dt, dt_.back());
    }
    const double last_dt = dt_.back();
    // The terminal value: the last column's field held for terminal_s more
    // (by default as long as crossing the field's depths takes).
    const double terminal_s = o_.terminal_s ? *o_.terminal_s : span / o_.vertical_speed_mps;
    const long extra = to_count(std::ceil(terminal_s / last_dt - 1e-9), 0, kMaxTerminalSteps);
    for (long e = 0; e < extra; ++e) dt_.push_back(last_dt);
    last_dt_ = last_dt;
    // The plan's step divides the shortest reach, no coarser than 10 m or the field.
    double spacing = kMaxPlanStep_m;
    for (std::size_t j = 1; j < f_.depth_m.size(); ++j) spacing = std::min(spacing, f_.depth_m[j] - f_.depth_m[j - 1]);
    const double reach = o_.vertical_speed_mps * min_dt;
    const double per_reach = static_cast<double>(to_count(std::ceil(reach / spacing - 1e-9), 1, kMaxStepsPerReach));
    h_ = std::max({reach / per_reach, span / kMaxPlanNodes, kMinPlanStep_m});
    // At most kMaxPlanNodes + 1 nodes: h ≥ span / kMaxPlanNodes.
    const long up = to_count(std::floor((zs_ - top) / h_ + 1e-9), 0, kMaxPlanNodes);
    const long down = to_count(std::floor((f_.depth_m.back() - zs_) / h_ + 1e-9), 0,
                               kMaxPlanNodes - static_cast<double>(up));
    start_ = static_cast<std::size_t>(up);
    nodes_ = static_cast<std::size_t>(up + down + 1);
    // (At most 127 grid steps a column: uneven columns plan a little slow.)
    for (double dt : dt_)
      moves_.push_back(to_count(std::floor(o_.vertical_speed_mps * dt / h_ + 1e-9), 0, kMaxMovesPerStep));
    // Each column's score on the plan's grid (kOutside: forbidden), and how
    // many nodes each is from the column's nearest allowed one.
    value_.assign(n, std::vector<double>(nodes_, kOutside));
    outside_.assign(n, std::vector<int>(nodes_, kNoAllowed));
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t i = 0; i < nodes_; ++i)
        if (allowed_at(f_.depth_m, f_.allowed[k], depth(i))) {
          value_[k][i] = cell(k, depth(i));
          outside_[k][i] = 0;
        }
      for (std::size_t i = 1; i < nodes_; ++i)
        if (outside_[k][i - 1] != kNoAllowed) outside_[k][i] = std::min(outside_[k][i], outside_[k][i - 1] + 1);
      for (std::size_t i = nodes_ - 1; i-- > 0;)
        if (outside_[k][i + 1] != kNoAllowed) outside_[k][i] = std::min(outside_[k][i], outside_[k][i + 1] + 1);
      // Outside: the further, the lower (down to −2), so the way back is
      // at full speed and not only as soon.
      for (std::size_t i = 0; i < nodes_; ++i)
        if (outside_[k][i] != 0)
          value_[k][i] = outside_[k][i] == kNoAllowed
                             ? 2 * kOutside
                             : kOutside * (1 + std::min(1.0, static_cast<double>(outside_[k][i]) * h_ / std::max(span, h_)));
    }
  }

  double depth(std::size_t i) const { return zs_ + (static_cast<double>(i) - static_cast<double>(start_)) * h_; }

  ForecastDecision plan() const {
    const std::size_t n = f_.time_s.size(), layers = dt_.size() + 1;
    auto column = [&](std::size_t l) { return std::min(l, n - 1); };
    // Backward: best[i] = the most a path from node i at layer l gathers.
    std::vector<double> best(nodes_), next(nodes_);
    for (std::size_t i = 0; i < nodes_; ++i) best[i] = value_[n - 1][i] * last_dt_;
    std::vector<std::vector<std::int8_t>> move(layers - 1, std::vector<std::int8_t>(nodes_, 0));
    for (std::size_t l = layers - 1; l-- > 0;) {
      next.swap(best);
      const std::vector<double>& v = value_[column(l)];
      const std::vector<int>& away = outside_[column(l + 1)];
      for (std::size_t i = 0; i < nodes_; ++i) {
        best[i] = kNever;
        if (l == 0 && i != start_) continue;
        for (long m = 0; m <= moves_[l]; ++m)
          for (long sign : {-1L, 1L}) {
            if (m == 0 && sign > 0) continue;  // ties go to the smallest move, up first
            const long j = static_cast<long>(i) + sign * m;
            if (j < 0 || j >= static_cast<long>(nodes_) || next[j] == kNever) continue;
            // A forbidden depth only on the way back into the allowed ones.
            if (away[j] != 0 && !(away[j] < away[i])) continue;
            const double gathered = dt_[l] * 0.5 * (v[i] + v[j]) + next[j];
            if (best[i] == kNever || gathered > best[i] + 1e-12 * std::max(1.0, std::abs(best[i]))) {
              best[i] = gathered;
              move[l][i] = static_cast<std::int8_t>(sign * m);
            }
          }
      }
    }
    ForecastDecision d;
    d.target_depth_m = z0_;
    d.path_time_s = f_.time_s;
    d.path_depth_m.assign(n, z0_);
    // Hold: nothing ahead receives (0), or no way at all; a negative best
    // is the way back into the allowed depths, and is taken.
    if (best[start_] == kNever || best[start_] == 0) return d;
    std::vector<std::size_t> node{start_};
    for (std::size_t l = 0; l + 1 < n; ++l) node.push_back(static_cast<std::size_t>(static_cast<long>(node.back()) + move[l][node.back()]));
    double sum = 0, span = 0;
    auto received = [&](std::size_t k, std::size_t i) { return std::max(0.0, value_[k][i]); };
    for (std::size_t k = 0; k < n; ++k) {
      if (k > 0) d.path_depth_m[k] = depth(node[k]);
      const double dt = k + 1 < n ? dt_[k] : last_dt_;
      const double s = k + 1 < n ? 0.5 * (received(k, node[k]) + received(k, node[k + 1])) : received(k, node[k]);
      sum += dt * s;
      span += dt;
    }
    d.expected_score = sum / span;
    d.choice = on_ridge(node) ? ForecastChoice::kRidge : ForecastChoice::kOptimum;
    // The target: the plan's best point after now, the earliest.
    std::size_t at = n > 1 ? 1 : 0;
    for (std::size_t k = 1; k < n; ++k)
      if (value_[k][node[k]] > value_[at][node[at]]) at = k;
    d.target_depth_m = d.path_depth_m[at];
    d.target_time_s = f_.time_s[at];
    d.target_objective = received(at, node[at]);
    d.vertical_rate_mps = d.target_time_s > 0 ? std::abs(d.target_depth_m - z0_) / d.target_time_s : 0;
    return d;
  }

 private:
  // The score of allowed depth z in column k: 0 in shadow.
  double cell(std::size_t k, double z) const {
    if (at_depth(f_.depth_m, f_.raw[k], z) <= o_.shadow_objective) return 0;
    const auto& s = f_.score.empty() ? f_.steer[k] : f_.score[k];
    return std::clamp(at_depth(f_.depth_m, s, z), 0.0, 1.0);
  }

  // On a ridge: at every column of the plan its depth scores above 0 and
  // within ridge_tolerance of the best within one field spacing around it,
  // in that column or the one before (a column's time ends one window and
  // starts the next: a plan on a moving ridge sits between the two).
  bool on_ridge(const std::vector<std::size_t>& node) const {
    double spacing = 0;
    for (std::size_t j = 1; j < f_.depth_m.size(); ++j) spacing = std::max(spacing, f_.depth_m[j] - f_.depth_m[j - 1]);
    const long around = to_count(std::ceil(std::max(spacing, h_) / h_ - 1e-9), 1, kMaxPlanNodes);
    auto near_top = [&](std::size_t k, std::size_t i) {
      const double here = value_[k][i];
      if (!(here > 0)) return false;
      for (long m = -around; m <= around; ++m) {
        const long j = static_cast<long>(i) + m;
        if (j >= 0 && j < static_cast<long>(nodes_) && value_[k][j] > here + o_.ridge_tolerance) return false;
      }
      return true;
    };
    for (std::size_t k = 0; k < node.size(); ++k)
      if (!near_top(k, node[k]) && !(k > 0 && near_top(k - 1, node[k]))) return false;
    return true;
  }

  const ForecastField& f_;
  double z0_, zs_ = 0;  // the vehicle's depth; the plan's start, within the field
  const ForecastOptions& o_;
  std::vector<double> dt_;  // per step between layers
  double last_dt_ = 0;
  double h_ = 0;
  std::size_t start_ = 0, nodes_ = 0;
  std::vector<long> moves_;                 // per step: how many grid steps w·Δt allows
  std::vector<std::vector<double>> value_;  // [column][node]
  std::vector<std::vector<int>> outside_;   // [column][node]: nodes to the nearest allowed (0: allowed)
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
  if (choice == ForecastChoice::kHold || dt <= 0 || path_time_s.size() < 2) return z0;
  double t_prev = 0, z_prev = z0;
  for (std::size_t k = 1; k < path_time_s.size(); ++k) {
    if (dt <= path_time_s[k]) return z_prev + (path_depth_m[k] - z_prev) * (dt - t_prev) / (path_time_s[k] - t_prev);
    t_prev = path_time_s[k];
    z_prev = path_depth_m[k];
  }
  return z_prev;
}

std::optional<std::string> validate_forecast_field(const ForecastField& f) {
  if (f.depth_m.empty()) return "the forecast field has no depths";
  if (!std::isfinite(f.depth_m.front()) || !std::isfinite(f.depth_m.back()))
    return "the forecast field's depths must be finite";
  if (!std::isfinite(f.time_s.empty() ? 0 : f.time_s.back())) return "the forecast field's times must be finite";
  for (std::size_t j = 1; j < f.depth_m.size(); ++j)
    if (!(f.depth_m[j] > f.depth_m[j - 1])) return "the forecast field's depths must be strictly increasing";
  if (f.time_s.empty() || f.time_s[0] != 0) return "the forecast field's first column must be at time 0";
  for (std::size_t k = 1; k < f.time_s.size(); ++k)
    if (!(f.time_s[k] > f.time_s[k - 1])) return "the forecast field's times must be strictly increasing";
  const std::size_t nk = f.time_s.size(), nj = f.depth_m.size();
  if (f.steer.size() != nk || f.raw.size() != nk || f.allowed.size() != nk || (!f.score.empty() && f.score.size() != nk))
    return "the forecast field needs one steer, raw, allowed (and score, if any) column per time";
  for (std::size_t k = 0; k < nk; ++k) {
    if (f.steer[k].size() != nj || f.raw[k].size() != nj || f.allowed[k].size() != nj ||
        (!f.score.empty() && f.score[k].size() != nj))
      return "forecast column " + std::to_string(k) + " does not have one value per depth";
    for (std::size_t j = 0; j < nj; ++j)
      if (!std::isfinite(f.steer[k][j]) || !std::isfinite(f.raw[k][j]) ||
          (!f.score.empty() && !std::isfinite(f.score[k][j])))
        return "forecast column " + std::to_string(k) + " holds a value that is not finite";
  }
  return std::nullopt;
}

std::optional<std::string> validate_forecast_options(const ForecastOptions& o) {
  if (auto e = require_greater("vertical_speed_mps", o.vertical_speed_mps, 0.0)) return e;
  if (!(o.vertical_speed_mps <= kMaxVerticalSpeed_mps))
    return "vertical_speed_mps = " + format_number(o.vertical_speed_mps) + " must be at most " +
           format_number(kMaxVerticalSpeed_mps) + " m/s";
  if (!(o.ridge_tolerance >= 0 && o.ridge_tolerance <= 1)) return "ridge_tolerance must be in [0, 1]";
  if (!(o.shadow_objective >= 0 && o.shadow_objective < 1)) return "shadow_objective must be in [0, 1)";
  if (o.terminal_s && !(*o.terminal_s >= 0 && *o.terminal_s <= kMaxTerminal_s))
    return "terminal_s must be in [0, " + format_number(kMaxTerminal_s) + "] s";
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
  if (r.reception)
    if (auto e = validate_reception_curve(*r.reception, "reception_")) return e;
  return validate_forecast_options(r.options);
}

ForecastDecision forecast_depth(const ForecastField& field, double z0, const ForecastOptions& options) {
  if (auto e = validate_forecast_field(field)) throw std::invalid_argument(*e);
  if (auto e = validate_forecast_options(options)) throw std::invalid_argument(*e);
  if (!std::isfinite(z0)) throw std::invalid_argument("current_depth_m must be finite");
  if (field.time_s.size() < 2) {  // the window now only: nothing to plan
    ForecastDecision d;
    d.target_depth_m = z0;
    d.path_time_s = field.time_s;
    d.path_depth_m = {z0};
    return d;
  }
  return Planner(field, z0, options).plan();
}

}  // namespace acomms::gram
