// The Micro-Modem prediction's hot path (node/link_prediction.h): what each
// packet heard costs the core thread once the TL grid is there, against
// what resolving and serializing GRAM's environment costs (what every
// packet paid before the environment was cached per version). Free-field
// water as in tests/unit/node/link_prediction_test.cpp; the time depends on
// the machine's load: reported, not enforced.
//
//   build/tests/bench/link_prediction_bench [--packets=N]
//   build/tests/bench/link_prediction_bench --smoke     (what ctest runs)
#include <google/protobuf/text_format.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

#include "gram/model_engine.h"
#include "gram/model_pool.h"
#include "gram/vehicle_environment.h"
#include "node/link_prediction.h"
#include "free_field_environment.h"

using namespace acomms;

namespace {

// Free field (free_field_environment.h): TL is 20 log10(r).
constexpr const char* kFreeField = acomms::test::kFreeFieldEnvironment;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  long packets = 200000;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--smoke") == 0) packets = 1000;
    else if (std::strncmp(argv[i], "--packets=", 10) == 0) packets = std::max(1L, std::atol(argv[i] + 10));
    else {
      std::fprintf(stderr, "usage: link_prediction_bench [--packets=N] [--smoke]\n");
      return 2;
    }
  }
  gram::Environment base;
  if (!google::protobuf::TextFormat::ParseFromString(kFreeField, &base)) return 1;
  gram::VehicleEnvironment environment(base, gram::VehicleEnvironmentOptions{});
  gram::ModelPool pool(gram::ModelPoolOptions{1, 16, 1 << 20}, gram::make_builtin_engine());
  std::mutex mutex;
  std::deque<std::function<void()>> tasks;  // this thread is the "core"
  core::NodePosition own;
  node::ModemPositions others;
  drivers::MicroModemPrediction config;
  google::protobuf::TextFormat::ParseFromString(
      "source_level_db: 190 noise_level_db: 85 max_range_m: 1000 range_step_m: 10 "
      "fixed { modem: 1 position { x: 300 y: 0 z: -10 } } fixed { modem: 2 position { x: 0 y: 0 z: -10 } }",
      &config);
  node::PredictionSources sources{1, &own, &others, &environment, &pool,
                                  [&](std::function<void()> task) {
                                    std::lock_guard lock(mutex);
                                    tasks.push_back(std::move(task));
                                  },
                                  [] { return 1'700'000'000.0; }};
  auto prediction = node::LinkPrediction::create(config, sources);
  v1::ModemTransmission heard;
  heard.set_src(2);
  v1::LinkFigures figures;
  prediction->predict(heard, figures);  // asks for the grid
  for (int i = 0; i < 6000 && prediction->counters().grids == 0; ++i) {
    std::deque<std::function<void()>> now;
    {
      std::lock_guard lock(mutex);
      now.swap(tasks);
    }
    for (auto& task : now) task();
    if (now.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (prediction->counters().grids == 0) {
    std::fprintf(stderr, "no TL grid in 60 s\n");
    return 1;
  }

  auto start = std::chrono::steady_clock::now();
  double sink = 0;
  for (long i = 0; i < packets; ++i) {
    v1::LinkFigures f;
    prediction->predict(heard, f);
    sink += f.predicted_snr_db();
  }
  const double per_packet = seconds_since(start) / double(packets);

  start = std::chrono::steady_clock::now();
  size_t bytes = 0;
  for (long i = 0; i < packets; ++i) {
    std::vector<gram::Environment> resolved = environment.resolve(gram::Environment(), {}, false);
    bytes += resolved.front().SerializeAsString().size();
  }
  const double resolve_per_packet = seconds_since(start) / double(packets);

  std::printf("link prediction, %ld packets: predict %.0f ns per packet (environment resolved %llu times); "
              "resolving and serializing the environment, what each packet paid before: %.0f ns\n",
              packets, per_packet * 1e9, static_cast<unsigned long long>(prediction->counters().water_resolved),
              resolve_per_packet * 1e9);
  return sink != 0 && bytes > 0 ? 0 : 1;
}
