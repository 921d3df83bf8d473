#include "eval/censored_excess_loss.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace acomms::eval {
namespace {

constexpr double kZ95 = 1.959964;
constexpr double kMinSpreadDb = 0.05;
constexpr int kMaxEvaluations = 20000;

using Params = Eigen::Vector4d;  // μ, ln σ, s50, ln w

// ln Φ(x), finite far into the lower tail (erfc underflows below −37).
double log_normal_cdf(double x) {
  if (x > -30) return std::log(0.5 * std::erfc(-x / std::numbers::sqrt2));
  return -0.5 * x * x - std::log(-x) - 0.5 * std::log(2 * std::numbers::pi);
}

double log_likelihood(const std::vector<PacketSample>& samples, const Params& q) {
  const double mu = q(0), sigma = std::exp(q(1)), s50 = q(2), w = std::exp(q(3));
  const double both = std::sqrt(sigma * sigma + w * w);
  double sum = 0;
  for (const PacketSample& s : samples) {
    if (s.measured_snr_db) {
      const double m = *s.measured_snr_db;
      const double e = (m - s.predicted_snr_db - mu) / sigma;
      sum += -0.5 * e * e - q(1) + log_normal_cdf((m - s50) / w);
    } else {
      const double z = (s.predicted_snr_db + mu - s50) / both;
      sum += log_normal_cdf(s.decoded ? z : -z);
    }
  }
  return sum;
}

// Nelder–Mead on −ℓ from `start` with initial steps `step`; the best point.
Params minimise(const std::vector<PacketSample>& samples, Params start, const Params& step, bool* converged) {
  auto f = [&](const Params& q) {
    const double v = -log_likelihood(samples, q);
    return std::isfinite(v) ? v : INFINITY;
  };
  std::array<Params, 5> x;
  std::array<double, 5> fx;
  x[0] = start;
  for (int i = 0; i < 4; ++i) {
    x[i + 1] = start;
    x[i + 1](i) += step(i);
  }
  for (int i = 0; i < 5; ++i) fx[i] = f(x[i]);
  int evaluations = 5;
  *converged = false;
  while (evaluations < kMaxEvaluations) {
    std::array<int, 5> order = {0, 1, 2, 3, 4};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return fx[a] < fx[b]; });
    std::array<Params, 5> xs;
    std::array<double, 5> fs;
    for (int i = 0; i < 5; ++i) {
      xs[i] = x[order[i]];
      fs[i] = fx[order[i]];
    }
    x = xs;
    fx = fs;
    // Converged when the value and μ, σ, s50 settle; ln w may drift on
    // towards −∞ where the threshold is hard (the likelihood flattens there).
    double size = 0;
    for (int i = 1; i < 5; ++i) size = std::max(size, (x[i] - x[0]).head<3>().cwiseAbs().maxCoeff());
    if (std::abs(fx[4] - fx[0]) < 1e-10 * (1 + std::abs(fx[0])) && size < 1e-7) {
      *converged = true;
      break;
    }
    Params centroid = (x[0] + x[1] + x[2] + x[3]) / 4;
    Params reflected = centroid + (centroid - x[4]);
    double fr = f(reflected);
    ++evaluations;
    if (fr < fx[0]) {
      Params expanded = centroid + 2 * (centroid - x[4]);
      double fe = f(expanded);
      ++evaluations;
      if (fe < fr) {
        x[4] = expanded, fx[4] = fe;
      } else {
        x[4] = reflected, fx[4] = fr;
      }
    } else if (fr < fx[3]) {
      x[4] = reflected, fx[4] = fr;
    } else {
      Params contracted = fr < fx[4] ? Params(centroid + 0.5 * (reflected - centroid))
                                     : Params(centroid + 0.5 * (x[4] - centroid));
      double fc = f(contracted);
      ++evaluations;
      if (fc < std::min(fr, fx[4])) {
        x[4] = contracted, fx[4] = fc;
      } else {
        for (int i = 1; i < 5; ++i) {
          x[i] = x[0] + 0.5 * (x[i] - x[0]);
          fx[i] = f(x[i]);
          ++evaluations;
        }
      }
    }
  }
  return x[0];
}

std::string format(const char* pattern, auto... values) {
  char text[512];
  std::snprintf(text, sizeof text, pattern, values...);
  return text;
}

}  // namespace

std::optional<CensoredExcessLossFit> fit_censored_excess_loss(const std::vector<PacketSample>& samples,
                                                              std::string* why) {
  std::size_t measured = 0, lost = 0;
  double mean = 0, sum2 = 0;
  for (const PacketSample& s : samples) {
    if (s.measured_snr_db) {
      ++measured;
      const double d = *s.measured_snr_db - s.predicted_snr_db;
      const double delta = d - mean;
      mean += delta / double(measured);
      sum2 += delta * (d - mean);
    }
    if (!s.decoded) ++lost;
  }
  if (measured < kMinMeasured) {
    *why = format("too few decoded packets with a measured SNR for the censored fit: %zu, at least %zu needed",
                  measured, kMinMeasured);
    return std::nullopt;
  }
  if (lost < kMinEachOutcome) {
    *why = format("%zu packets lost: at least %zu needed for the censored fit (with none lost, the decoded "
                  "packets are not a biased sample)",
                  lost, kMinEachOutcome);
    return std::nullopt;
  }
  const double spread = std::sqrt(sum2 / double(measured - 1));
  if (spread < kMinSpreadDb) {
    *why = format("the measured SNRs scatter by %.3f dB about the model: no scatter, no survivors' bias to "
                  "correct",
                  spread);
    return std::nullopt;
  }
  // Start: the decoded-only estimate, and a threshold at the lowest SNR
  // that decoded.
  double lowest = INFINITY;
  for (const PacketSample& s : samples) {
    if (s.measured_snr_db) lowest = std::min(lowest, *s.measured_snr_db);
  }
  Params start(mean, std::log(spread), lowest, std::log(std::max(spread, 1.0)));
  bool converged = false;
  Params best = minimise(samples, start, Params(1, 0.3, 1, 0.3), &converged);
  // Once more from where it stopped: a simplex can collapse early.
  if (converged) best = minimise(samples, best, Params(0.5, 0.1, 0.5, 0.1), &converged);
  best(3) = std::max(best(3), std::log(1e-6));  // a hard threshold: w ≈ 0
  if (!converged || !best.allFinite() || std::exp(best(1)) > 100) {
    *why = "the censored fit does not converge on these data";
    return std::nullopt;
  }
  // μ's interval: the inverse of the observed information (numerical Hessian
  // of −ℓ by central differences).
  Eigen::Matrix4d hessian;
  const double h = 1e-3;
  for (int i = 0; i < 4; ++i) {
    for (int j = i; j < 4; ++j) {
      auto at = [&](double di, double dj) {
        Params q = best;
        q(i) += di;
        q(j) += dj;
        return -log_likelihood(samples, q);
      };
      const double v = (at(h, h) - at(h, -h) - at(-h, h) + at(-h, -h)) / (4 * h * h);
      hessian(i, j) = hessian(j, i) = v;
    }
  }
  // With a hard threshold ln w is not identified (the likelihood is flat
  // there): μ's variance then comes from the other three, w held.
  double var_mu = hessian.fullPivLu().isInvertible() ? hessian.inverse()(0, 0) : NAN;
  if (!(std::isfinite(var_mu) && var_mu > 0)) {
    const Eigen::Matrix3d three = hessian.topLeftCorner<3, 3>();
    var_mu = three.fullPivLu().isInvertible() ? three.inverse()(0, 0) : NAN;
  }
  // No curvature at the optimum: the data do not pin μ down, and an
  // interval of ±0 would claim they do.
  if (!(std::isfinite(var_mu) && var_mu > 0)) {
    *why = "the censored fit's offset has no finite confidence interval on these data";
    return std::nullopt;
  }
  CensoredExcessLossFit fit;
  fit.packets = samples.size();
  fit.measured = measured;
  fit.offset_db = best(0);
  fit.spread_db = std::exp(best(1));
  fit.snr50_db = best(2);
  fit.width_db = std::exp(best(3));
  fit.offset_ci95_db = kZ95 * std::sqrt(var_mu);
  return fit;
}

}  // namespace acomms::eval
