// Speed and memory of the built-in acoustic model (daemon/gram) on the three
// benchmark environments of shared/conformance/gram/envs, with the beam
// counts the files give (never fewer: the run fails if it would use fewer).
// Goals (issue 16): bench_munk_query under 5 ms in process; on two threads,
// bench_munk_field under 0.35 s with under 100 MB, bench_shallow_25k under
// 0.3 s. Each case runs in a child process so its peak RSS is its own; the
// time is the median of the repetitions, in process (the .env is parsed
// once, outside the timing). Prints figures on 1 and 2 threads.
//
//   build/tests/bench/gram_bench [--repeat=N]
//   build/tests/bench/gram_bench --smoke      (what ctest runs: one quick case)
//   build/tests/bench/gram_bench --case=bench_shallow_25k --threads=1 --repeat=1
//                                  (one case in process, e.g. under callgrind)

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "gram/beam_fan.h"
#include "gram/bellhop_import.h"
#include "gram/transmission_loss.h"

namespace {

using namespace acomms::gram;

struct Case {
  const char* name;
  double goal_s;     // on two threads (the query: in process, any threads)
  double goal_mb;    // 0: none
  int repeat_scale;  // quick cases repeat more
};

// Runs one case in this (child) process: prints its line, returns 0 if met.
int run_case(const Case& c, unsigned threads, int repeat) {
  const std::string path = std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/" + c.name + ".env";
  const Environment env = import_bellhop_env_file(path).environment;
  std::vector<double> seconds;
  std::uint32_t beams = 0;
  for (int i = 0; i < repeat * c.repeat_scale; ++i) {
    const auto start = std::chrono::steady_clock::now();
    const auto tl = compute_transmission_loss(env, {threads});
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    beams = tl.beam_count;
  }
  std::sort(seconds.begin(), seconds.end());
  const double median = seconds[seconds.size() / 2];
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double mb = usage.ru_maxrss / 1024.0;
  const bool enough_beams = env.beam_count() == 0 || beams >= env.beam_count();
  const bool time_met = threads != 2 || median <= c.goal_s;
  const bool memory_met = c.goal_mb == 0 || mb <= c.goal_mb;
  std::printf("%-18s %6u beams  %u thread(s)  median %8.4f s  peak RSS %6.1f MB   goal %.3f s%s  %s\n",
              c.name, beams, threads, median, mb, c.goal_s, c.goal_mb > 0 ? ", 100 MB" : "",
              threads == 2 ? (time_met && memory_met ? "met" : "NOT met") : "");
  if (!enough_beams) {
    std::printf("  used %u beams, fewer than the file's %u\n", beams, env.beam_count());
    return 2;
  }
  return 0;
}

int in_child(const Case& c, unsigned threads, int repeat) {
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0) {
    const int code = run_case(c, threads, repeat);
    std::fflush(stdout);  // _exit does not flush
    _exit(code);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 3;
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  bool smoke = false;
  const char* only = nullptr;
  unsigned only_threads = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--smoke") == 0) smoke = true;
    else if (std::strncmp(argv[i], "--repeat=", 9) == 0) repeat = std::max(1, std::atoi(argv[i] + 9));
    else if (std::strncmp(argv[i], "--case=", 7) == 0) only = argv[i] + 7;
    else if (std::strncmp(argv[i], "--threads=", 10) == 0) only_threads = std::max(1, std::atoi(argv[i] + 10));
    else {
      std::fprintf(stderr, "usage: gram_bench [--repeat=N] [--smoke] [--case=NAME [--threads=N]]\n");
      return 2;
    }
  }
  const std::vector<Case> cases = {{"bench_munk_query", 0.005, 0, 20},
                                   {"bench_munk_field", 0.35, 100, 1},
                                   {"bench_shallow_25k", 0.3, 0, 1}};
  if (smoke) return in_child(cases[0], 2, 1);
  if (only) {
    // One case, in this process (no fork), so a profiler sees all of it.
    for (const Case& c : cases)
      if (std::strcmp(c.name, only) == 0) {
        if (only_threads) return run_case(c, only_threads, repeat);
        int failures = 0;
        for (unsigned threads : {1u, 2u}) failures += in_child(c, threads, repeat) != 0;
        return failures;
      }
    std::fprintf(stderr, "gram_bench: no case named %s\n", only);
    return 2;
  }
  int failures = 0;
  for (const Case& c : cases)
    for (unsigned threads : {1u, 2u}) failures += in_child(c, threads, repeat) != 0;
  // Goals are reported, not enforced: timings depend on the machine's load.
  return failures == 0 ? 0 : 1;
}
