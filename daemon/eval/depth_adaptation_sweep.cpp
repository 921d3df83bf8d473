#include "eval/depth_adaptation_sweep.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace acomms::eval {
namespace {

std::string fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

double binomial_se(double p, std::uint32_t n) { return n ? std::sqrt(p * (1 - p) / n) : 0.0; }

const char* unit_name(SweepQuantity q) { return q == SweepQuantity::kNoise ? "noise_db" : "excess_loss_db"; }

// One number of FROM:TO:STEP, all of it.
double number(const std::string& text, const std::string& what, const std::string& whole) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
    throw std::invalid_argument("sweep range \"" + whole + "\": " + what + " \"" + text +
                                "\" is not a number (FROM:TO:STEP in dB, e.g. 100:112:2)");
  }
  return v;
}

}  // namespace

SweepQuantity sweep_quantity_from_string(const std::string& name) {
  if (name == "noise") return SweepQuantity::kNoise;
  if (name == "excess-loss") return SweepQuantity::kExcessLoss;
  throw std::invalid_argument("cannot sweep \"" + name + "\" (known: noise, excess-loss)");
}

SweepRange parse_sweep_range(const std::string& text) {
  const auto first = text.find(':');
  const auto second = first == std::string::npos ? std::string::npos : text.find(':', first + 1);
  if (second == std::string::npos || text.find(':', second + 1) != std::string::npos) {
    throw std::invalid_argument("sweep range \"" + text + "\" is not FROM:TO:STEP (in dB, e.g. 100:112:2)");
  }
  SweepRange r;
  r.from = number(text.substr(0, first), "FROM", text);
  r.to = number(text.substr(first + 1, second - first - 1), "TO", text);
  r.step = number(text.substr(second + 1), "STEP", text);
  if (!(r.step > 0)) throw std::invalid_argument("sweep range \"" + text + "\": STEP must be > 0");
  if (r.to < r.from) throw std::invalid_argument("sweep range \"" + text + "\": TO must be at least FROM");
  if ((r.to - r.from) / r.step + 1 > kMaxSweepPoints + 1e-6) {
    throw std::invalid_argument("sweep range \"" + text + "\" has more than " + std::to_string(kMaxSweepPoints) +
                                " values: raise STEP");
  }
  return r;
}

std::vector<double> sweep_values(const SweepRange& range) {
  std::vector<double> values;
  // By index, not by adding STEP: no drift, and TO is reached when it lies
  // on the grid (up to rounding).
  for (int i = 0;; ++i) {
    const double v = range.from + i * range.step;
    if (v > range.to + 1e-6 * range.step) break;
    values.push_back(v);
  }
  return values;
}

std::vector<SweepPoint> run_depth_adaptation_sweep(const gram::Environment& env, const DepthAdaptationConfig& config,
                                                   const gram::Environment* vehicle_model, SweepQuantity quantity,
                                                   const SweepRange& range) {
  std::vector<SweepPoint> points;
  // One model run: only the physics changes from value to value.
  const DepthAdaptationModel model = model_depth_adaptation(env, config, vehicle_model);
  for (double value : sweep_values(range)) {
    gram::LinkPhysics physics = config.physics;
    if (quantity == SweepQuantity::kNoise) {
      physics.noise_level_db = value;
    } else {
      physics.site.excess_loss_db = value;
    }
    const DepthAdaptationResult r = replay_depth_adaptation(model, physics);
    const StrategyResult& a = r.strategies.back();
    const StrategyResult& f = r.strategies[r.best_fixed];
    SweepPoint p;
    p.value = value;
    p.adaptive = a.receipt_overall();
    p.adaptive_se = binomial_se(p.adaptive, a.total_sent);
    p.best_fixed = f.name;
    p.fixed = f.receipt_overall();
    p.fixed_se = binomial_se(p.fixed, f.total_sent);
    const double se = std::hypot(p.adaptive_se, p.fixed_se);
    p.margin_se = se > 0 ? (p.adaptive - p.fixed) / se : 0.0;
    points.push_back(p);
  }
  return points;
}

std::string format_sweep_table(SweepQuantity quantity, const DepthAdaptationConfig& config,
                               const std::vector<SweepPoint>& points) {
  std::string out = std::string("sweep of ") +
                    (quantity == SweepQuantity::kNoise ? "the band noise level NL (dB re 1 uPa)"
                                                       : "the site's excess loss (dB)") +
                    ": " + std::to_string(config.laps) + " laps each (seed " + std::to_string(config.seed) +
                    "); SE = sqrt(p(1-p)/n); margin in SEs of the difference (conservative: the strategies share "
                    "their draws)\n";
  char line[160];
  std::snprintf(line, sizeof line, "%10s %9s %7s %10s %9s %7s %9s  %s\n", quantity == SweepQuantity::kNoise ? "NL_dB" : "excess_dB",
                "adaptive", "SE", "best_fixed", "receipt", "SE", "margin", "verdict");
  out += line;
  for (const SweepPoint& p : points) {
    const char* verdict = p.margin_se > 2 ? "adaptation helps" : p.margin_se < -2 ? "a fixed depth is better"
                                                                                   : "no clear difference";
    std::snprintf(line, sizeof line, "%10.1f %9.3f %7.3f %10s %9.3f %7.3f %+9.1f  %s\n", p.value, p.adaptive,
                  p.adaptive_se, p.best_fixed.c_str(), p.fixed, p.fixed_se, p.margin_se, verdict);
    out += line;
  }
  return out;
}

std::string format_sweep_json(SweepQuantity quantity, const std::vector<SweepPoint>& points) {
  std::string out = std::string("{\"quantity\":\"") + unit_name(quantity) + "\",\"points\":[";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SweepPoint& p = points[i];
    if (i) out += ',';
    out += "{\"value\":" + fixed(p.value, 3) + ",\"adaptive\":" + fixed(p.adaptive, 6) +
           ",\"adaptive_se\":" + fixed(p.adaptive_se, 6) + ",\"best_fixed\":\"" + p.best_fixed +
           "\",\"fixed\":" + fixed(p.fixed, 6) + ",\"fixed_se\":" + fixed(p.fixed_se, 6) +
           ",\"margin_se\":" + fixed(p.margin_se, 3) + "}";
  }
  return out + "]}\n";
}

}  // namespace acomms::eval
