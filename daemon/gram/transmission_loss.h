// Transmission loss on a receiver grid: the public entry of the model.
//
// Problem: GRAM and acommsctl need TL from an Environment, quickly and
// reproducibly. Decision: the fan (spec §4.7) is split into a fixed number
// of interleaved chunks (every K-th beam) that depends only on the grid
// size, never on the thread count; each chunk sums its beams in order into
// its own buffer and the buffers are added in chunk order. Threads only
// choose which chunk to run, and then which receivers' sums (each in chunk
// order) to add up, so the result is bit-identical whatever their number.
// Thread-safe: each call is independent.
#pragma once

#include <complex>
#include <cstdint>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "gram/cancel_token.h"

namespace acomms::gram {

struct RunOptions {
  // 0: the hardware's concurrency. At most this many; a small run (a few
  // thousand ray steps) runs on the calling thread alone.
  unsigned threads = 0;
  // Polled once per beam; when cancelled the run throws ModelCancelled.
  const CancelToken* cancel = nullptr;
  // Keep the field itself (TransmissionLoss::pressure), e.g. to write a
  // .shd; off by default, as most callers want TL only.
  bool keep_pressure = false;
};

struct TransmissionLoss {
  std::vector<double> range_m;  // the environment's receiver ranges
  std::vector<double> depth_m;  // and depths
  bool irregular = false;
  // Grid: tl_db[iz · n_ranges + ir]; irregular: one per receiver pair.
  // +inf where no beam reaches (shadow); NaN at range 0 (no value).
  std::vector<double> tl_db;
  // With RunOptions::keep_pressure, in tl_db's order: the coherent field p
  // (spec §0 convention, TL = −20 log10 |p|); incoherent and semi-coherent
  // runs: √intensity, real. 0 where tl_db has no value. Else empty.
  std::vector<std::complex<double>> pressure;
  std::uint32_t beam_count = 0;  // the count used (automatic if the input gave 0)
};

// Throws std::invalid_argument with validate_environment's message, or
// ModelCancelled when options.cancel was cancelled during the run.
TransmissionLoss compute_transmission_loss(const Environment& env, const RunOptions& options = {});

}  // namespace acomms::gram
