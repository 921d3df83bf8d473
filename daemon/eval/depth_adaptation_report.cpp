// Text and JSON reports of the depth-adaptation experiment.
#include <cmath>
#include <cstdio>
#include <string>

#include "eval/depth_adaptation.h"

namespace acomms::eval {
namespace {

std::string fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

}  // namespace

double receipt_se(const StrategyResult& s) {
  const double p = s.receipt_overall();
  return s.total_sent ? std::sqrt(p * (1 - p) / s.total_sent) : 0.0;
}

namespace {

std::string bin_label(const DepthAdaptationResult& r, std::size_t b) {
  return fixed(r.bin_edges_m[b], 0) + "-" + fixed(r.bin_edges_m[b + 1], 0);
}

// One honest sentence: who received most, and whether adaptation helped,
// in the draws and in the model's expectation.
std::string verdict(const DepthAdaptationResult& r) {
  const StrategyResult& a = r.strategies.back();
  const StrategyResult& f = r.strategies[r.best_fixed];
  std::size_t e = 0;
  for (std::size_t s = 0; s < r.strategies.size(); ++s)
    if (r.strategies[s].fixed_depth_m && r.strategies[s].expected_overall > r.strategies[e].expected_overall) e = s;
  std::string out = r.adaptive_beats_every_fixed ? "adaptation helps here" : "adaptation does NOT help here";
  out += ": adaptive receives " + fixed(a.receipt_overall(), 3) + " against " + fixed(f.receipt_overall(), 3) +
         " at the best fixed depth (" + f.name + "); expected " + fixed(a.expected_overall, 4) + " against " +
         fixed(r.strategies[e].expected_overall, 4) + " (" + r.strategies[e].name + ")";
  if (r.adaptive_beats_every_fixed != r.adaptive_expected_beats_every_fixed)
    out += "; the draws and the expectation disagree: the difference is within sampling noise (raise --laps)";
  out += "\n";
  for (const StrategyResult& s : r.strategies) {
    if (s.name != "forecast") continue;
    const double se = std::hypot(receipt_se(s), receipt_se(a));
    out += "forecast receives " + fixed(s.receipt_overall(), 3) + " (SE " + fixed(receipt_se(s), 3) +
           ") against the next window's " + fixed(a.receipt_overall(), 3) + " (SE " + fixed(receipt_se(a), 3) +
           "): " + (se > 0 ? fixed((s.receipt_overall() - a.receipt_overall()) / se, 1) : std::string("0.0")) +
           " SEs of the difference; against the best fixed depth " +
           (std::hypot(receipt_se(s), receipt_se(f)) > 0
                ? fixed((s.receipt_overall() - f.receipt_overall()) / std::hypot(receipt_se(s), receipt_se(f)), 1)
                : std::string("0.0")) +
           " SEs\n";
  }
  return out;
}

}  // namespace

std::string format_depth_adaptation_table(const DepthAdaptationConfig& c, const DepthAdaptationResult& r) {
  std::string out = "buoy at " + fixed(c.buoy_depth_m, 1) + " m; vehicle out " + fixed(c.start_range_m, 0) + " -> " +
                    fixed(c.max_range_m, 0) + " m and back at " + fixed(c.speed_mps, 2) + " m/s, a rate-" +
                    std::to_string(c.rate) + " packet every " + fixed(c.send_interval_s, 0) + " s, " +
                    std::to_string(c.laps) + " laps (seed " + std::to_string(c.seed) + ")\n";
  out += "model: " + std::to_string(r.beam_count) + " beams, " + std::to_string(r.model_ranges) + " ranges x " +
         std::to_string(r.model_depths) + " depths; SL " + fixed(c.physics.source_level_db, 1) + " dB, NL " +
         fixed(r.noise_level_db, 1) + " dB" +
         (c.noise_decrease_db_per_km ? ", falling " + fixed(*c.noise_decrease_db_per_km, 1) + " dB/km below " +
                                           (r.critical_depth_m ? fixed(*r.critical_depth_m, 0) + " m" : "no depth")
                                     : std::string()) +
         "; adaptive: tau_a " + fixed(c.horizon_s, 0) + " s, " +
         (c.noise_decrease_db_per_km ? std::string("by signal excess") : "H_max " + fixed(c.h_max_db, 0) + " dB") +
         (c.forecast ? ", forecast over " + fixed(c.forecast_horizon_s, 0) + " s" : std::string()) + ", at most " + fixed(c.vertical_speed_mps, 2) + " m/s vertically, deciding on " +
         (r.separate_model ? "its own model" : "the water itself (a perfect model)") + "\n";
  out += "receipt probability per range bin (m)\n";
  char cell[64];
  std::snprintf(cell, sizeof cell, "%-10s", "strategy");
  out += cell;
  for (std::size_t b = 0; b + 1 < r.bin_edges_m.size(); ++b) {
    std::snprintf(cell, sizeof cell, " %10s", bin_label(r, b).c_str());
    out += cell;
  }
  out += "    overall     SE  expected  mean_depth_m\n";
  for (const StrategyResult& s : r.strategies) {
    std::snprintf(cell, sizeof cell, "%-10s", s.name.c_str());
    out += cell;
    for (std::size_t b = 0; b < s.sent.size(); ++b) {
      std::snprintf(cell, sizeof cell, " %10.3f", s.receipt(b));
      out += cell;
    }
    std::snprintf(cell, sizeof cell, " %10.3f %6.3f %9.3f %13.1f\n", s.receipt_overall(), receipt_se(s),
                  s.expected_overall, s.mean_depth_m);
    out += cell;
  }
  return out + verdict(r);
}

std::string format_depth_adaptation_json(const DepthAdaptationConfig& c, const DepthAdaptationResult& r) {
  std::string out = "{\"buoy_depth_m\":" + fixed(c.buoy_depth_m, 3) + ",\"max_range_m\":" + fixed(c.max_range_m, 3) +
                    ",\"speed_mps\":" + fixed(c.speed_mps, 3) + ",\"send_interval_s\":" + fixed(c.send_interval_s, 3) +
                    ",\"rate\":" + std::to_string(c.rate) + ",\"laps\":" + std::to_string(c.laps) +
                    ",\"seed\":" + std::to_string(c.seed) + ",\"beam_count\":" + std::to_string(r.beam_count) +
                    ",\"source_level_db\":" + fixed(c.physics.source_level_db, 3) + ",\"noise_level_db\":" +
                    fixed(r.noise_level_db, 3) + ",\"bin_edges_m\":[";
  for (std::size_t b = 0; b < r.bin_edges_m.size(); ++b) {
    if (b) out += ',';
    out += fixed(r.bin_edges_m[b], 3);
  }
  out += "],\"strategies\":[";
  for (std::size_t i = 0; i < r.strategies.size(); ++i) {
    const StrategyResult& s = r.strategies[i];
    out += i ? ",{" : "{";
    out += "\"name\":\"" + s.name + "\",";
    out += s.fixed_depth_m ? "\"fixed_depth_m\":" + fixed(*s.fixed_depth_m, 3) + "," : "\"adaptive\":true,";
    auto list = [&](const char* key, auto value) {
      out += std::string("\"") + key + "\":[";
      for (std::size_t b = 0; b < s.sent.size(); ++b) {
        if (b) out += ',';
        out += value(b);
      }
      out += "],";
    };
    list("sent", [&](std::size_t b) { return std::to_string(s.sent[b]); });
    list("received", [&](std::size_t b) { return std::to_string(s.received[b]); });
    list("receipt", [&](std::size_t b) { return fixed(s.receipt(b), 6); });
    list("expected", [&](std::size_t b) { return fixed(s.expected[b], 6); });
    out += "\"receipt_overall\":" + fixed(s.receipt_overall(), 6) + ",\"expected_overall\":" +
           fixed(s.expected_overall, 6) + ",\"mean_depth_m\":" + fixed(s.mean_depth_m, 3) + "}";
  }
  out += "],\"adaptive_beats_every_fixed\":";
  out += r.adaptive_beats_every_fixed ? "true" : "false";
  out += ",\"adaptive_expected_beats_every_fixed\":";
  out += r.adaptive_expected_beats_every_fixed ? "true" : "false";
  out += ",\"best_fixed\":\"" + r.strategies[r.best_fixed].name + "\",\"separate_model\":";
  out += r.separate_model ? "true}\n" : "false}\n";
  return out;
}

}  // namespace acomms::eval
