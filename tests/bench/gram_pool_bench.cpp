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
#include <cstdio>
#include <cstring>
#include <string>

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
  return failures == 0 ? 0 : 1;
}
