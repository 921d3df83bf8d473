#include "eval/link_calibration.h"

#include "eval/censored_excess_loss.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace acomms::eval {
namespace {

constexpr double kZ95 = 1.959964;  // normal approximation of the 95% intervals
constexpr int kMaxIterations = 100;
// A slope steeper than this (1/dB: 12% to 88% within 0.04 dB) is no fit but
// the separation Newton's method runs off to infinity on.
constexpr double kMaxSlopePerDb = 100;

std::string format(const char* pattern, auto... values) {
  char text[512];
  std::snprintf(text, sizeof text, pattern, values...);
  return text;
}

std::string on_link(const LinkCalibration& link) {
  return link.link.empty() ? std::string() : " on link \"" + link.link + "\"";
}

}  // namespace

std::vector<PacketSample> packet_samples(const std::vector<v1::Event>& events, std::size_t* skipped) {
  std::vector<PacketSample> out;
  std::size_t left_out = 0;
  for (const v1::Event& e : events) {
    if (e.kind() != "packet") continue;
    const v1::LinkFigures& f = e.link();
    if (!f.has_predicted_snr_db() || !std::isfinite(f.predicted_snr_db())) {
      ++left_out;
      continue;
    }
    PacketSample s;
    s.link = f.link();
    s.src = f.transmission_src() != 0 ? f.transmission_src() : e.src();
    s.rate = f.rate();
    s.time = e.time();
    s.decoded = f.decoded();
    if (s.decoded && f.has_snr_in_db() && std::isfinite(f.snr_in_db())) s.measured_snr_db = f.snr_in_db();
    s.predicted_snr_db = f.predicted_snr_db();
    out.push_back(s);
  }
  if (skipped != nullptr) *skipped = left_out;
  return out;
}

std::optional<ExcessLossFit> fit_excess_loss(const std::vector<PacketSample>& samples, std::string* why) {
  std::vector<double> d;
  for (const PacketSample& s : samples) {
    if (s.measured_snr_db) d.push_back(*s.measured_snr_db - s.predicted_snr_db);
  }
  if (d.size() < kMinMeasured) {
    *why = format("too few decoded packets with a measured SNR to fit an excess loss: %zu, at least %zu needed",
                  d.size(), kMinMeasured);
    return std::nullopt;
  }
  ExcessLossFit fit;
  fit.packets = d.size();
  fit.offset_db = std::accumulate(d.begin(), d.end(), 0.0) / double(d.size());
  double sum2 = 0;
  for (double v : d) sum2 += (v - fit.offset_db) * (v - fit.offset_db);
  fit.spread_db = std::sqrt(sum2 / double(d.size() - 1));
  fit.offset_ci95_db = kZ95 * fit.spread_db / std::sqrt(double(d.size()));
  return fit;
}

std::optional<ReceptionFit> fit_reception_curve(const std::vector<PacketSample>& samples, std::string* why) {
  const std::size_t n = samples.size();
  std::size_t decoded = 0;
  double lowest_decoded = INFINITY, highest_lost = -INFINITY, mean = 0;
  for (const PacketSample& s : samples) {
    mean += s.predicted_snr_db;
    if (s.decoded) {
      ++decoded;
      lowest_decoded = std::min(lowest_decoded, s.predicted_snr_db);
    } else {
      highest_lost = std::max(highest_lost, s.predicted_snr_db);
    }
  }
  if (n < kMinPackets) {
    *why = format("too few packets to fit a reception curve: %zu, at least %zu needed", n, kMinPackets);
    return std::nullopt;
  }
  if (decoded < kMinEachOutcome || n - decoded < kMinEachOutcome) {
    *why = format("%zu of %zu packets decoded: at least %zu decoded and %zu lost are needed to place the 50%% "
                  "point (the data must span the threshold)",
                  decoded, n, kMinEachOutcome, kMinEachOutcome);
    return std::nullopt;
  }
  if (highest_lost < lowest_decoded) {
    *why = format("every lost packet was predicted below %.1f dB and every decoded one above %.1f dB: the curve's "
                  "slope is unbounded (more packets near the threshold are needed)",
                  highest_lost, lowest_decoded);
    return std::nullopt;
  }
  mean /= double(n);
  // P = σ(a + b (x − mean)), Newton's method on the log-likelihood (IRLS).
  Eigen::Vector2d beta = Eigen::Vector2d::Zero();
  Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
  bool converged = false;
  for (int iteration = 0; iteration < kMaxIterations && !converged; ++iteration) {
    Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
    information.setZero();
    for (const PacketSample& s : samples) {
      const Eigen::Vector2d x(1.0, s.predicted_snr_db - mean);
      const double p = 1.0 / (1.0 + std::exp(-beta.dot(x)));
      gradient += ((s.decoded ? 1.0 : 0.0) - p) * x;
      information += p * (1 - p) * x * x.transpose();
    }
    const Eigen::Vector2d step = information.ldlt().solve(gradient);
    if (!step.allFinite()) break;
    beta += step;
    converged = step.norm() < 1e-10 * (1 + beta.norm());
  }
  const double a = beta(0), b = beta(1);
  if (!converged || !(b > 0) || b > kMaxSlopePerDb) {
    *why = format("the reception curve does not fit (slope %.3g per dB after Newton's method): the decoding does "
                  "not rise with the predicted SNR in these data",
                  b);
    return std::nullopt;
  }
  const Eigen::Matrix2d covariance = information.inverse();
  ReceptionFit fit;
  fit.packets = n;
  fit.decoded = decoded;
  fit.slope_per_db = b;
  fit.snr50_predicted_db = mean - a / b;
  // Delta method for x50 = mean − a/b.
  const double var_x50 = covariance(0, 0) / (b * b) + a * a * covariance(1, 1) / (b * b * b * b) -
                         2 * a * covariance(0, 1) / (b * b * b);
  fit.snr50_ci95_db = kZ95 * std::sqrt(std::max(0.0, var_x50));
  fit.slope_ci95_per_db = kZ95 * std::sqrt(std::max(0.0, covariance(1, 1)));
  return fit;
}

bool LinkCalibration::fitted() const {
  if (excess) return true;
  return std::any_of(rates.begin(), rates.end(), [](const auto& r) { return r.second.curve.has_value(); });
}

double LinkCalibration::offset_db() const {
  if (censored) return censored->offset_db;
  return excess ? excess->offset_db : 0.0;
}

double LinkCalibration::physics_snr50_db(const ReceptionFit& curve) const {
  return curve.snr50_predicted_db + offset_db();
}

std::vector<LinkCalibration> calibrate_links(const std::vector<PacketSample>& samples) {
  std::map<std::pair<std::string, int32_t>, std::vector<PacketSample>> by_link;
  for (const PacketSample& s : samples) by_link[{s.link, s.src}].push_back(s);
  std::vector<LinkCalibration> out;
  for (const auto& [key, link_samples] : by_link) {
    LinkCalibration link;
    link.link = key.first;
    link.src = key.second;
    link.packets = link_samples.size();
    link.excess = fit_excess_loss(link_samples, &link.excess_refused);
    if (link.excess) {
      if (auto censored = fit_censored_excess_loss(link_samples, &link.censored_refused)) {
        link.censored = std::make_shared<const CensoredExcessLossFit>(*censored);
      }
    }
    std::map<int32_t, std::vector<PacketSample>> by_rate;
    for (const PacketSample& s : link_samples) by_rate[s.rate].push_back(s);
    for (const auto& [rate, rate_samples] : by_rate) {
      RateCalibration& r = link.rates[rate];
      r.packets = rate_samples.size();
      r.decoded = static_cast<std::size_t>(
          std::count_if(rate_samples.begin(), rate_samples.end(), [](const PacketSample& s) { return s.decoded; }));
      r.curve = fit_reception_curve(rate_samples, &r.curve_refused);
    }
    out.push_back(std::move(link));
  }
  return out;
}

std::string physics_block(const LinkCalibration& link) {
  std::string out = format("# acommsctl link calibrate: packets from modem %d%s (%zu heard)\n", link.src,
                           on_link(link).c_str(), link.packets);
  out += "physics {\n";
  if (link.censored) {
    out += format("  # measured - predicted SNR: %.2f dB over decoded packets only (spread %.2f dB, %zu packets)\n",
                  link.excess->offset_db, link.excess->spread_db, link.excess->packets);
    out += format("  # censored fit, lost packets counted: %.2f dB (spread %.2f dB, +/- %.2f dB at 95%%, %zu "
                  "packets)\n",
                  link.censored->offset_db, link.censored->spread_db, link.censored->offset_ci95_db,
                  link.censored->packets);
    out += format("  excess_loss_db: %.2f\n", -link.censored->offset_db);
  } else if (link.excess) {
    out += format("  # measured - predicted SNR: %.2f dB (spread %.2f dB, +/- %.2f dB at 95%%, %zu packets)\n",
                  link.excess->offset_db, link.excess->spread_db, link.excess->offset_ci95_db, link.excess->packets);
    out += format("  excess_loss_db: %.2f\n", link.excess->excess_loss_db());
  } else {
    out += "  # no excess loss: " + link.excess_refused + "\n";
  }
  for (const auto& [rate, r] : link.rates) {
    if (!r.curve) {
      out += format("  # rate %d: no reception curve: %s\n", rate, r.curve_refused.c_str());
      continue;
    }
    out += format("  # rate %d: 50%% at predicted SNR %.2f +/- %.2f dB, slope %.3f +/- %.3f per dB (%zu packets)\n",
                  rate, r.curve->snr50_predicted_db, r.curve->snr50_ci95_db, r.curve->slope_per_db,
                  r.curve->slope_ci95_per_db, r.curve->packets);
    out += format("  reception { rate: %d snr50_db: %.2f slope_per_db: %.3f }\n", rate, link.physics_snr50_db(*r.curve),
                  r.curve->slope_per_db);
  }
  out += "}\n";
  return out;
}

std::string calibration_report(const std::vector<LinkCalibration>& links) {
  std::string out;
  for (const LinkCalibration& link : links) {
    out += format("link from modem %d%s: %zu packets\n", link.src, on_link(link).c_str(), link.packets);
    if (link.excess) {
      out += format("  excess loss %.2f dB +/- %.2f (95%%); measured - predicted SNR: offset %.2f dB, spread %.2f dB "
                    "(%zu packets)\n",
                    link.excess->excess_loss_db(), link.excess->offset_ci95_db, link.excess->offset_db,
                    link.excess->spread_db, link.excess->packets);
      if (link.censored) {
        out += format("  censored fit (lost packets counted): excess loss %.2f dB +/- %.2f (95%%), spread %.2f dB "
                      "(%zu packets): the decoded-only mean is biased by %+.2f dB\n",
                      -link.censored->offset_db, link.censored->offset_ci95_db, link.censored->spread_db,
                      link.censored->packets, link.excess->offset_db - link.censored->offset_db);
      } else {
        out += "  censored fit: not fitted: " + link.censored_refused + "\n";
      }
    } else {
      out += "  excess loss: not fitted: " + link.excess_refused + "\n";
    }
    for (const auto& [rate, r] : link.rates) {
      out += format("  rate %d: %zu packets, %zu decoded\n", rate, r.packets, r.decoded);
      if (r.curve) {
        out += format("    reception curve: 50%% at %.2f dB +/- %.2f predicted SNR (%.2f dB in the physics' "
                      "corrected SNR), slope %.3f +/- %.3f per dB (95%%)\n",
                      r.curve->snr50_predicted_db, r.curve->snr50_ci95_db, link.physics_snr50_db(*r.curve),
                      r.curve->slope_per_db, r.curve->slope_ci95_per_db);
      } else {
        out += "    reception curve: not fitted: " + r.curve_refused + "\n";
      }
    }
  }
  return out;
}

}  // namespace acomms::eval
