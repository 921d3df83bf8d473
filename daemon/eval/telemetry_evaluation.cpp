#include "eval/telemetry_evaluation.h"

#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "telemetry/telemetry_decoder.h"
#include "telemetry/telemetry_encoder.h"
#include "util/splitmix64.h"

namespace acomms::eval {
namespace {

using telemetry::DecodeOutcome;
using telemetry::EncodedMessage;
using telemetry::MessageKind;

bool parse_number(const std::string& text, double* value) {
  try {
    size_t used = 0;
    *value = std::stod(text, &used);
    return used == text.size() && std::isfinite(*value);
  } catch (const std::exception&) {
    return false;
  }
}

// Decodes message as the receiver would and checks it against what was sent.
void check_decoded(telemetry::TelemetryDecoder& decoder, const EncodedMessage& message,
                   const telemetry::Sample& sample, uint64_t index) {
  const telemetry::DecodedMessage decoded = decoder.decode(message.bytes);
  const int64_t time = telemetry::unwrap_time_of_day(decoded.time_s, sample.time_s);
  if (decoded.outcome != DecodeOutcome::kPosition || decoded.kind != message.kind ||
      decoded.grid != message.position || time != sample.time_s) {
    throw std::runtime_error("telemetry sample " + std::to_string(index) + " at t=" +
                             std::to_string(sample.time_s) + " s did not decode to what was sent");
  }
}

struct LossOutcome {
  double delta_bits_per_position = 0, newest_bits_per_position = 0, extra_latency_s = 0;
  uint64_t packets = 0;
};

// The slot-by-slot resend simulation described in the header; decodes each
// delivered message in order.
LossOutcome simulate_loss(const std::vector<EncodedMessage>& messages, const std::vector<telemetry::Sample>& samples,
                          const telemetry::TelemetryConfig& config, const TelemetryLossConfig& loss,
                          uint64_t full_bits) {
  util::SplitMix64 random(loss.seed);
  telemetry::TelemetryDecoder decoder(config);
  std::deque<size_t> pending;
  uint64_t sent_bits = 0, packets = 0, delivered = 0;
  double latency_sum = 0;
  uint64_t newest_delivered = 0;
  const size_t n = messages.size();
  for (size_t slot = 0; slot < n || !pending.empty(); ++slot) {
    if (slot < n) pending.push_back(slot);
    const int64_t now = slot < n ? samples[slot].time_s : samples.back().time_s +
                                                             static_cast<int64_t>(slot - n + 1) * config.tau_s;
    const bool lost = random.uniform() < loss.loss;
    if (slot < n && !lost) ++newest_delivered;  // the newest-full scheme in the same slot
    // Pack the oldest undelivered messages (at least one).
    size_t count = 0;
    uint64_t bits = 0;
    while (count < pending.size() && (count == 0 || bits + messages[pending[count]].bits <= loss.packet_bits))
      bits += messages[pending[count++]].bits;
    sent_bits += bits;
    ++packets;
    if (lost) continue;
    for (size_t i = 0; i < count; ++i) {
      const size_t k = pending.front();
      pending.pop_front();
      check_decoded(decoder, messages[k], samples[k], k);
      latency_sum += static_cast<double>(now - samples[k].time_s);
      ++delivered;
    }
  }
  LossOutcome outcome;
  outcome.packets = packets;
  outcome.delta_bits_per_position = static_cast<double>(sent_bits) / static_cast<double>(delivered);
  outcome.newest_bits_per_position =
      newest_delivered == 0 ? INFINITY : static_cast<double>(full_bits * n) / static_cast<double>(newest_delivered);
  outcome.extra_latency_s = latency_sum / static_cast<double>(delivered);
  return outcome;
}

std::string fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

}  // namespace

std::vector<telemetry::Fix> read_track_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the track file");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(path + ": empty, expected the header t,x,y,z");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != "t,x,y,z") throw std::runtime_error(path + ":1: expected the header t,x,y,z, got '" + line + "'");
  std::vector<telemetry::Fix> fixes;
  for (int number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::stringstream fields(line);
    std::string field;
    double values[4];
    int count = 0;
    while (std::getline(fields, field, ',')) {
      if (count == 4 || !parse_number(field, &values[count]))
        throw std::runtime_error(path + ":" + std::to_string(number) + ": expected four numbers t,x,y,z, got '" +
                                 line + "'");
      ++count;
    }
    if (count != 4)
      throw std::runtime_error(path + ":" + std::to_string(number) + ": expected four numbers t,x,y,z, got '" +
                               line + "'");
    if (!fixes.empty() && values[0] <= fixes.back().time_s)
      throw std::runtime_error(path + ":" + std::to_string(number) + ": time " + std::to_string(values[0]) +
                               " does not increase (previous " + std::to_string(fixes.back().time_s) + ")");
    fixes.push_back(telemetry::Fix{values[0], {values[1], values[2], values[3]}});
  }
  if (fixes.empty()) throw std::runtime_error(path + ": no fixes after the header");
  return fixes;
}

TelemetryRun evaluate_telemetry(const std::vector<telemetry::Sample>& samples,
                                const telemetry::TelemetryConfig& config, const TelemetryLossConfig& loss) {
  if (!(loss.loss >= 0 && loss.loss <= 0.95)) throw std::invalid_argument("loss must be within [0, 0.95]");
  TelemetryRun run;
  run.observer = config.observer;
  run.model = config.model;
  telemetry::TelemetryEncoder encoder(config);
  telemetry::TelemetryDecoder decoder(config);
  std::vector<EncodedMessage> messages;
  messages.reserve(samples.size());
  double delta_sum = 0, delta_sum_sq = 0, message_sum = 0;
  for (size_t i = 0; i < samples.size(); ++i) {
    EncodedMessage message = encoder.encode(samples[i]);
    check_decoded(decoder, message, samples[i], i);
    if (message.kind == MessageKind::kDelta) {
      ++run.deltas;
      const double bits = static_cast<double>(message.body_bits);
      delta_sum += bits;
      delta_sum_sq += bits * bits;
    } else {
      ++run.fulls;
      run.full_bits = message.bits;
    }
    message_sum += static_cast<double>(message.bits);
    messages.push_back(std::move(message));
  }
  run.positions = samples.size();
  if (run.deltas > 0) {
    const double n = static_cast<double>(run.deltas);
    run.delta_bits_mean = delta_sum / n;
    run.delta_bits_std = std::sqrt(std::max(0.0, delta_sum_sq / n - run.delta_bits_mean * run.delta_bits_mean));
    run.delta_compression_pct = 100 * (1 - run.delta_bits_mean / 96);
  }
  if (run.positions > 0) {
    run.message_bits_mean = message_sum / static_cast<double>(run.positions);
    run.overall_compression_pct = 100 * (1 - run.message_bits_mean / 96);
  }
  if (loss.loss > 0 && !messages.empty()) {
    const LossOutcome outcome = simulate_loss(messages, samples, config, loss, run.full_bits);
    run.with_loss = true;
    run.loss_delta_bits_per_position = outcome.delta_bits_per_position;
    run.loss_newest_bits_per_position = outcome.newest_bits_per_position;
    run.loss_extra_latency_s = outcome.extra_latency_s;
    run.loss_packets = outcome.packets;
  }
  return run;
}

std::string format_telemetry_table(const std::vector<TelemetryRun>& runs) {
  std::string out =
      "observer     model     positions  deltas  fulls  delta_bits  delta_std  bits_per_position  "
      "delta_vs_96  overall_vs_96";
  const bool loss = !runs.empty() && runs[0].with_loss;
  if (loss) out += "  resend_bits_per_position  newest_full_bits_per_position  extra_latency_s";
  out += "\n";
  char line[512];
  for (const TelemetryRun& r : runs) {
    std::snprintf(line, sizeof line, "%-12s %-9s %9llu %7llu %6llu %11s %10s %18s %11s%% %13s%%",
                  std::string(telemetry::name_of(r.observer)).c_str(), std::string(telemetry::name_of(r.model)).c_str(),
                  static_cast<unsigned long long>(r.positions), static_cast<unsigned long long>(r.deltas),
                  static_cast<unsigned long long>(r.fulls), fixed(r.delta_bits_mean, 2).c_str(),
                  fixed(r.delta_bits_std, 2).c_str(), fixed(r.message_bits_mean, 2).c_str(),
                  fixed(r.delta_compression_pct, 1).c_str(), fixed(r.overall_compression_pct, 1).c_str());
    out += line;
    if (loss) {
      std::snprintf(line, sizeof line, "  %24s  %29s  %15s", fixed(r.loss_delta_bits_per_position, 2).c_str(),
                    fixed(r.loss_newest_bits_per_position, 2).c_str(), fixed(r.loss_extra_latency_s, 1).c_str());
      out += line;
    }
    out += "\n";
  }
  return out;
}

std::string format_telemetry_json(const std::string& track, uint64_t fixes, const std::vector<TelemetryRun>& runs) {
  std::string out = "{\"track\":\"";
  for (char c : track) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += "\",\"fixes\":" + std::to_string(fixes) + ",\"runs\":[";
  for (size_t i = 0; i < runs.size(); ++i) {
    const TelemetryRun& r = runs[i];
    out += i == 0 ? "{" : ",{";
    out += "\"observer\":\"" + std::string(telemetry::name_of(r.observer)) + "\",\"model\":\"" +
           std::string(telemetry::name_of(r.model)) + "\",\"positions\":" + std::to_string(r.positions) +
           ",\"deltas\":" + std::to_string(r.deltas) + ",\"fulls\":" + std::to_string(r.fulls) +
           ",\"delta_bits_mean\":" + fixed(r.delta_bits_mean, 4) + ",\"delta_bits_std\":" +
           fixed(r.delta_bits_std, 4) + ",\"bits_per_position\":" + fixed(r.message_bits_mean, 4) +
           ",\"full_bits\":" + std::to_string(r.full_bits) + ",\"delta_compression_pct\":" +
           fixed(r.delta_compression_pct, 2) + ",\"overall_compression_pct\":" + fixed(r.overall_compression_pct, 2);
    if (r.with_loss) {
      out += ",\"resend_bits_per_position\":" + fixed(r.loss_delta_bits_per_position, 4) +
             ",\"newest_full_bits_per_position\":" + fixed(r.loss_newest_bits_per_position, 4) +
             ",\"extra_latency_s\":" + fixed(r.loss_extra_latency_s, 3) + ",\"packets\":" +
             std::to_string(r.loss_packets);
    }
    out += "}";
  }
  out += "]}\n";
  return out;
}

}  // namespace acomms::eval
