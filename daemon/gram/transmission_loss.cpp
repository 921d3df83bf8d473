// The run: fan, chunks, threads, TL. shared/spec/gram.md §4.7–§4.10, §9.
#include "gram/transmission_loss.h"

#include <sys/mman.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <numbers>
#include <span>
#include <stdexcept>
#include <thread>

#include "gram/beam_fan.h"
#include "gram/beam_influence.h"
#include "gram/environment_validation.h"
#include "gram/medium.h"
#include "gram/ray.h"
#include "gram/receiver_grid.h"

namespace acomms::gram {
namespace {

// Chunk buffers are bounded to about this many bytes in all.
constexpr std::size_t kChunkBudgetBytes = 48u << 20;
constexpr std::size_t kMaxChunks = 8;

// The chunks' sums: up to 48 MB that every run zeroes and then adds to at
// random. Filled by vector::assign they cost one fault per 4 kB page (the
// kernel zeroing it) and a second write of every byte: a third of the CPU
// time of a 201 × 1000 run (perf stat: 9,600 page faults, 27 ms of 79 in the
// kernel). Decision: sums of 2 MB or more are mapped anonymously (zero by
// the kernel's promise, so not written again) on 2 MB boundaries with
// MADV_HUGEPAGE, one fault per 2 MB where the kernel grants huge pages and
// small pages where it does not (the advice is only advice); smaller ones
// come from calloc.
constexpr std::size_t kHugePage = 2u << 20;

struct Release {
  std::size_t mapped_bytes = 0;  // 0: from calloc
  void operator()(void* p) const {
    if (mapped_bytes > 0) ::munmap(p, mapped_bytes);
    else std::free(p);
  }
};
template <typename T>
using ZeroedArray = std::unique_ptr<T[], Release>;

template <typename T>
ZeroedArray<T> zeroed(std::size_t n) {
  const std::size_t bytes = std::max<std::size_t>(n, 1) * sizeof(T);
  if (bytes < kHugePage) {
    void* p = std::calloc(std::max<std::size_t>(n, 1), sizeof(T));
    if (p == nullptr) throw std::bad_alloc();
    return ZeroedArray<T>(static_cast<T*>(p));
  }
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  // Map a huge page more, keep the aligned part, unmap the ends.
  void* raw = ::mmap(nullptr, rounded + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (start + kHugePage - 1) / kHugePage * kHugePage;
  if (aligned > start) ::munmap(raw, aligned - start);
  if (const std::size_t tail = start + kHugePage - aligned; tail > 0)
    ::munmap(reinterpret_cast<void*>(aligned + rounded), tail);
  void* p = reinterpret_cast<void*>(aligned);
  ::madvise(p, rounded, MADV_HUGEPAGE);  // refused: small pages, same values
  return ZeroedArray<T>(static_cast<T*>(p), Release{rounded});
}

// Chunk i traces beams i, i + K, i + 2K, ... (K chunks): interleaved, so
// every chunk holds steep and shallow beams alike and costs about the same
// (steep beams die in a few bounces, shallow ones run the whole range), and
// two threads finish together.
struct Chunk {
  std::uint32_t first_beam, stride;
  ZeroedArray<std::complex<double>> pressure;  // in the grid's slot order (coherent runs)
  ZeroedArray<double> intensity;               // (the other runs)
};

}  // namespace

TransmissionLoss compute_transmission_loss(const Environment& env, const RunOptions& options) {
  if (auto error = validate_environment(env)) throw std::invalid_argument(*error);
  const Medium medium(env);
  const ReceiverGrid receivers(env);
  const std::uint32_t beams = beam_count(env);
  const bool coherent = env.field_mode() == COHERENT;
  const BeamInfluence influence(medium, receivers, env.field_mode(), env.beam_shape());

  const double a1 = env.launch_angle_min_deg() * std::numbers::pi / 180.0;
  const double a2 = env.launch_angle_max_deg() * std::numbers::pi / 180.0;
  const double spacing = (a2 - a1) / (beams - 1);
  const double zs = env.source_depth_m();
  const double c_source = medium.ssp().at(zs, medium.ssp().layer_at(zs, 1.0)).c;
  const double k_source = medium.omega() / c_source;

  const std::size_t bytes_per_chunk = receivers.size() * (coherent ? 16 : 8);
  const std::size_t chunk_count = std::clamp<std::size_t>(
      kChunkBudgetBytes / std::max<std::size_t>(bytes_per_chunk, 1), 1,
      std::min<std::size_t>(kMaxChunks, beams));
  std::vector<Chunk> chunks(chunk_count);
  for (std::size_t i = 0; i < chunk_count; ++i) {
    chunks[i].first_beam = static_cast<std::uint32_t>(i);
    chunks[i].stride = static_cast<std::uint32_t>(chunk_count);
  }

  auto run_chunk = [&](Chunk& chunk) {
    if (coherent) chunk.pressure = zeroed<std::complex<double>>(receivers.size());
    else chunk.intensity = zeroed<double>(receivers.size());
    const std::span<std::complex<double>> pressure(chunk.pressure.get(), coherent ? receivers.size() : 0);
    const std::span<double> intensity(chunk.intensity.get(), coherent ? 0 : receivers.size());
    for (std::uint32_t m = chunk.first_beam; m < beams; m += chunk.stride) {
      if (options.cancel && options.cancel->cancelled()) return;  // thrown below, after the join
      const double angle = a1 + m * spacing;
      BeamLaunch launch{angle, std::abs(std::cos(angle)), spacing, c_source, 1.0};
      if (env.field_mode() == SEMI_COHERENT) {
        const double s = std::sin(k_source * zs * std::sin(launch.angle_rad));
        launch.intensity_factor = 2.0 * s * s;  // Lloyd-mirror source pattern (§4.10)
      }
      RayTracer ray(medium, launch.angle_rad);
      while (ray.next())
        influence.add(ray.previous(), ray.point(), launch, pressure, intensity);
    }
  };
  unsigned threads = options.threads ? options.threads : std::thread::hardware_concurrency();
  threads = std::clamp<unsigned>(threads, 1, static_cast<unsigned>(chunk_count));
  // A run of a few thousand ray steps takes about a millisecond: starting a
  // thread for it costs more than it saves on a busy machine (the thread
  // may wait a time slice to run). The estimate counts full-range rays at
  // the longest step; the result does not depend on the choice.
  constexpr double kStepsWorthAThread = 50'000;
  const double estimated_steps =
      static_cast<double>(beams) * std::ceil(medium.box_range() / medium.max_step());
  if (estimated_steps < kStepsWorthAThread) threads = 1;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < chunk_count;) run_chunk(chunks[i]);
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  throw_if_cancelled(options.cancel);

  TransmissionLoss result;
  result.range_m.assign(env.receiver_range_m().begin(), env.receiver_range_m().end());
  result.depth_m.assign(env.receiver_depth_m().begin(), env.receiver_depth_m().end());
  result.irregular = env.irregular_receivers();
  result.beam_count = beams;
  result.tl_db.assign(receivers.size(), 0.0);
  if (options.keep_pressure) result.pressure.assign(receivers.size(), {0.0, 0.0});
  const auto& outputs = receivers.slot_outputs();
  // Slots [first, last): the chunks' sums (in chunk order, whatever the
  // thread) and their TL. Each slot's value is its own and goes to its own
  // output index (slot_outputs is a permutation), so splitting the slots
  // over the run's threads gives the same bytes without a lock; on a
  // 201 × 1000 grid this loop (a log10 per receiver) was the longest part
  // left on one thread.
  auto reduce = [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i) {
      double power = 0.0;
      std::complex<double> p{0.0, 0.0};
      if (coherent) {
        for (const Chunk& chunk : chunks) p += chunk.pressure[i];
        power = std::norm(p);
      } else {
        for (const Chunk& chunk : chunks) power += chunk.intensity[i];
        if (options.keep_pressure) p = std::sqrt(power);
      }
      result.tl_db[outputs[i]] = power > 0 ? -10.0 * std::log10(power) : std::numeric_limits<double>::infinity();
      if (options.keep_pressure) result.pressure[outputs[i]] = p;
    }
  };
  constexpr std::size_t kSlotsWorthAThread = 20'000;
  const std::size_t parts = std::clamp<std::size_t>(receivers.size() / kSlotsWorthAThread, 1, threads);
  {
    std::vector<std::jthread> helpers;
    for (std::size_t k = 1; k < parts; ++k)
      helpers.emplace_back(reduce, receivers.size() * k / parts, receivers.size() * (k + 1) / parts);
    reduce(0, receivers.size() / parts);
  }
  for (const auto& column : receivers.columns())
    if (column.range_m <= 0)
      for (std::size_t index : column.index) {
        result.tl_db[index] = std::numeric_limits<double>::quiet_NaN();
        if (options.keep_pressure) result.pressure[index] = {0.0, 0.0};
      }
  return result;
}

}  // namespace acomms::gram
