// GRAM's worker pool (daemon/gram/model_pool.h) under load: requests per
// second and p99 latency (submit to answer) for bench_munk_query with 1 and
// 2 workers, cold (every request differs, so every one is a model run) and
// cached (the same request again: answered from the cache). Clients keep
// 2 × workers requests in flight (closed loop), in process: gRPC's own cost
// is not included. And how soon a run is stopped (model_pool.h promises
// "a fraction of a second"): from a ticket's cancel(), and from a request's
// deadline, to its answer, for a run far longer than either (the median of
// a few). Figures depend on the machine's load; they are reported, not
// enforced.
//
//   build/tests/bench/gram_pool_bench [--requests=N]
//   build/tests/bench/gram_pool_bench --smoke      (what ctest runs)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <future>
#include <string>
#include <thread>
#include <vector>

#include "closed_loop.h"
#include "gram/bellhop_import.h"
#include "gram/model_pool.h"

namespace {

using namespace acomms::gram;

using acomms::bench::ClosedLoopFigures;

ClosedLoopFigures run(const Environment& env, unsigned workers, bool cached, int requests) {
  ModelPool pool({workers, 1000, 256u << 20}, make_builtin_engine());
  auto issue = [&](int index, std::function<void(bool)> done) {
    ModelRequest r;
    r.environments = {env};
    // Cold: a source depth 1 µm apart per request: the same work, another key.
    if (!cached) r.environments[0].set_source_depth_m(env.source_depth_m() + 1e-6 * index);
    pool.submit(std::move(r), "", [done](ModelOutcome o) { done(o.status == ModelStatus::kOk); });
  };
  if (cached) acomms::bench::run_closed_loop(1, 1, issue);  // warm the cache with the one request
  return acomms::bench::run_closed_loop(requests, static_cast<int>(2 * workers), issue);
}

// A run far longer than any stop: the most beams on a dense grid.
ModelRequest slow_request(const Environment& env) {
  ModelRequest r;
  r.environments = {env};
  r.environments[0].set_beam_count(100000);
  r.environments[0].clear_receiver_range_m();
  for (int i = 1; i <= 2000; ++i) r.environments[0].add_receiver_range_m(5.0 * i);
  return r;
}

struct StopFigures {
  double median_ms = 0, max_ms = 0;
  int failed = 0;  // runs not answered with the stop's status
};

// From the stop (cancel() once the run has started, or the deadline) to the
// answer, over `runs` runs on one worker.
StopFigures time_stops(const Environment& env, bool by_deadline, int runs) {
  using Clock = std::chrono::steady_clock;
  ModelPool pool({1, 16, 256u << 20}, make_builtin_engine());
  StopFigures figures;
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    ModelRequest request = slow_request(env);
    request.environments[0].set_source_depth_m(env.source_depth_m() + 1e-6 * i);  // never a cache hit
    Clock::time_point stop_at = Clock::now() + std::chrono::milliseconds(100);
    if (by_deadline) request.deadline = stop_at;
    std::promise<ModelStatus> answered;
    auto ticket = pool.submit(std::move(request), "", [&](ModelOutcome o) { answered.set_value(o.status); });
    if (!by_deadline) {
      while (pool.stats().running == 0) std::this_thread::yield();  // running, not waiting
      stop_at = Clock::now();
      ticket->cancel();
    }
    const ModelStatus status = answered.get_future().get();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - stop_at).count());
    figures.failed += status != (by_deadline ? ModelStatus::kDeadlineExceeded : ModelStatus::kCancelled);
  }
  std::sort(ms.begin(), ms.end());
  figures.median_ms = ms[ms.size() / 2];
  figures.max_ms = ms.back();
  return figures;
}

}  // namespace

int main(int argc, char** argv) {
  int requests = 400;
  bool smoke = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--smoke") == 0) smoke = true;
    else if (std::strncmp(argv[i], "--requests=", 11) == 0) requests = std::max(10, std::atoi(argv[i] + 11));
    else {
      std::fprintf(stderr, "usage: gram_pool_bench [--requests=N] [--smoke]\n");
      return 2;
    }
  }
  const Environment env =
      import_bellhop_env_file(std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/bench_munk_query.env").environment;
  int failures = 0;
  for (unsigned workers : {1u, 2u})
    for (bool cached : {false, true}) {
      const int n = smoke ? 20 : (cached ? requests * 50 : requests);
      const ClosedLoopFigures f = run(env, workers, cached, n);
      std::printf("bench_munk_query  %u worker(s)  %-6s  %6d requests  %10.1f requests/s  p50 %8.3f ms  p99 %8.3f ms%s\n",
                  workers, cached ? "cached" : "cold", n, f.per_second, f.p50_ms, f.p99_ms,
                  f.failed ? "  FAILED" : "");
      failures += f.failed;
    }
  for (bool by_deadline : {false, true}) {
    const int runs = smoke ? 1 : 5;
    const StopFigures f = time_stops(env, by_deadline, runs);
    std::printf("stop a long run    %-8s to answer  %d run(s)  median %8.3f ms  max %8.3f ms%s\n",
                by_deadline ? "deadline" : "cancel", runs, f.median_ms, f.max_ms, f.failed ? "  FAILED" : "");
    failures += f.failed;
  }
  return failures == 0 ? 0 : 1;
}
