// GRAM's worker pool (daemon/gram/model_pool.h) under load: requests per
// second and p99 latency (submit to answer) for bench_munk_query with 1 and
// 2 workers, cold (every request differs, so every one is a model run) and
// cached (the same request again: answered from the cache). Clients keep
// 2 × workers requests in flight (closed loop), in process: gRPC's own cost
// is not included. Figures depend on the machine's load; they are
// reported, not enforced.
//
//   build/tests/bench/gram_pool_bench [--requests=N]
//   build/tests/bench/gram_pool_bench --smoke      (what ctest runs)

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "gram/bellhop_import.h"
#include "gram/model_pool.h"

namespace {

using namespace acomms::gram;
using Clock = std::chrono::steady_clock;

struct Figures {
  double per_second, p50_ms, p99_ms;
  int failed;
};

Figures run(const Environment& env, unsigned workers, bool cached, int requests) {
  ModelPool pool({workers, 1000, 256u << 20}, make_builtin_engine());
  if (cached) {  // warm the cache with the one request
    std::mutex m;
    std::condition_variable cv;
    bool done = false;
    ModelRequest r;
    r.environments = {env};
    pool.submit(r, "", [&](ModelOutcome) {
      std::lock_guard lock(m);
      done = true;
      cv.notify_all();
    });
    std::unique_lock lock(m);
    cv.wait(lock, [&] { return done; });
  }
  const int in_flight = static_cast<int>(2 * workers);
  std::mutex m;
  std::condition_variable cv;
  std::vector<double> latency_ms;
  int submitted = 0, answered = 0, failed = 0;
  std::function<void()> submit_one;
  submit_one = [&] {
    ModelRequest r;
    r.environments = {env};
    // Cold: a source depth 1 µm apart per request: the same work, another key.
    if (!cached) r.environments[0].set_source_depth_m(env.source_depth_m() + 1e-6 * submitted);
    ++submitted;
    const auto start = Clock::now();
    pool.submit(std::move(r), "", [&, start](ModelOutcome o) {
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      std::lock_guard lock(m);
      latency_ms.push_back(ms);
      if (o.status != ModelStatus::kOk) ++failed;
      ++answered;
      cv.notify_all();
    });
  };
  const auto start = Clock::now();
  std::unique_lock lock(m);
  while (answered < requests) {
    while (submitted < requests && submitted - answered < in_flight) {
      lock.unlock();
      submit_one();  // a cache hit answers inside submit, taking `m` itself
      lock.lock();
    }
    cv.wait(lock, [&] { return answered == requests || (submitted < requests && submitted - answered < in_flight); });
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::sort(latency_ms.begin(), latency_ms.end());
  auto at = [&](double q) { return latency_ms[std::min(latency_ms.size() - 1, static_cast<std::size_t>(q * latency_ms.size()))]; };
  return {requests / seconds, at(0.5), at(0.99), failed};
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
      const Figures f = run(env, workers, cached, n);
      std::printf("bench_munk_query  %u worker(s)  %-6s  %6d requests  %10.1f requests/s  p50 %8.3f ms  p99 %8.3f ms%s\n",
                  workers, cached ? "cached" : "cold", n, f.per_second, f.p50_ms, f.p99_ms,
                  f.failed ? "  FAILED" : "");
      failures += f.failed;
    }
  return failures == 0 ? 0 : 1;
}
