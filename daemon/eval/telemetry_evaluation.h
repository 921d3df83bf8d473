#pragma once
// Offline evaluation of position telemetry (Schneider 2013, sections 3.6-3.7):
// what a track costs in bits with each observer and probability model, and
// what loss does to cost and latency.
//
// Every message is decoded again by a TelemetryDecoder and compared with
// what the encoder meant to send (position and time): a mismatch is a bug
// and throws, it is never averaged into a statistic.
//
// Loss model (--loss P): one transmission slot per sample (every tau), a
// packet of packet_bits per slot, each packet lost with probability P
// (Bernoulli, seeded). Deltas must arrive in order, so everything not yet
// delivered is resent, oldest first, as much as fits in each packet.
// Compared with sending the newest position as a full transmission in every
// slot and never resending: mean bits per delivered position, and the extra
// latency (the newest scheme delivers its positions in the slot they are
// made, so the delta scheme's mean delivery delay is all extra).
//
// Thread-safe: an evaluation shares nothing with another.

#include <cstdint>
#include <string>
#include <vector>

#include "telemetry/sampler.h"
#include "telemetry/telemetry_config.h"

namespace acomms::eval {

// Reads "t,x,y,z" (seconds, metres, z negative down). Throws
// std::runtime_error naming the file, the line and what is wrong.
std::vector<telemetry::Fix> read_track_csv(const std::string& path);

struct TelemetryLossConfig {
  double loss = 0;             // P, in [0, 0.95]
  uint32_t packet_bits = 256;  // one Micro-Modem rate-0 frame (32 bytes)
  uint64_t seed = 1;
};

struct TelemetryRun {
  telemetry::ObserverKind observer{};
  telemetry::ModelKind model{};
  uint64_t positions = 0;
  uint64_t deltas = 0;
  uint64_t fulls = 0;
  // The arithmetic codeword of a delta (what the thesis reports).
  double delta_bits_mean = 0;
  double delta_bits_std = 0;
  // Whole messages (5-bit header included), deltas and fulls, per position.
  double message_bits_mean = 0;
  uint64_t full_bits = 0;  // one full message
  // 100 (1 - bits / 96): codeword per delta; messages per position.
  double delta_compression_pct = 0;
  double overall_compression_pct = 0;
  // With loss only (loss > 0 in the config).
  bool with_loss = false;
  double loss_delta_bits_per_position = 0;
  double loss_newest_bits_per_position = 0;
  double loss_extra_latency_s = 0;
  uint64_t loss_packets = 0;
};

// One observer and model over samples. Throws std::runtime_error when a
// message does not decode to what was sent.
TelemetryRun evaluate_telemetry(const std::vector<telemetry::Sample>& samples,
                                const telemetry::TelemetryConfig& config, const TelemetryLossConfig& loss);

std::string format_telemetry_table(const std::vector<TelemetryRun>& runs);
std::string format_telemetry_json(const std::string& track, uint64_t fixes, const std::vector<TelemetryRun>& runs);

}  // namespace acomms::eval
