// `acommsctl gram tl` as a user runs it: the whole process (start, .env
// import, model, formatting, writing the output to a file) on 2 threads,
// median of 5 runs, against the goals of issue 32 (half of bellhopcxx's
// time on the same 2-core machine kind): bench_munk_field 0.49 s,
// bench_shallow_25k 0.53 s, bench_munk_query 0.014 s, and the Lloyd-mirror
// field of tests/bench/envs (201 depths × 1000 ranges, 500 Hz, 2000
// coherent hat beams) 0.114 s. Prints figures; goals are reported, not
// enforced (timings depend on the machine's load). Run it alone, e.g.
// under the build lock on a shared machine. Beside the wall time it prints
// the process's CPU time (user + system, all threads, from wait4): on a
// loaded machine the wall time grows with the others' work, the CPU time
// much less, so it is the figure to compare a change by there.
//
//   build/tests/bench/gram_cli_bench [--repeat=N] [--format=csv|shd] [--case=NAME]
//                                    [--acommsctl=PATH]   (another build, e.g. before a change)
//   build/tests/bench/gram_cli_bench --smoke    (what ctest runs: one quick run)

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

struct Case {
  const char* name;
  std::string env;
  double goal_s;
};

struct Run {
  double seconds = 0;
  double cpu_seconds = 0;  // user + system, every thread
  long long output_bytes = 0;
  int status = 0;
};

// One `acommsctl gram tl` with stdout to `output`, stderr discarded.
Run run_once(const std::string& acommsctl, const std::string& env, const std::string& format,
             const std::string& output) {
  std::vector<std::string> args = {acommsctl, "gram", "tl", "--env", env, "--threads", "2"};
  if (!format.empty()) {
    args.push_back("--format");
    args.push_back(format);
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    const int out = open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = open("/dev/null", O_WRONLY);
    if (out < 0 || null < 0) _exit(126);
    dup2(out, 1);
    dup2(null, 2);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  struct rusage usage{};
  wait4(pid, &status, 0, &usage);
  Run run;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto seconds_of = [](const timeval& t) { return static_cast<double>(t.tv_sec) + t.tv_usec * 1e-6; };
  run.cpu_seconds = seconds_of(usage.ru_utime) + seconds_of(usage.ru_stime);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  struct stat st{};
  if (stat(output.c_str(), &st) == 0) run.output_bytes = st.st_size;
  return run;
}

int bench(const Case& c, const std::string& acommsctl, const std::string& format, int repeat) {
  const std::string output = "/tmp/gram_cli_bench_" + std::to_string(getpid()) + "." + (format.empty() ? "csv" : format);
  std::vector<double> seconds, cpu;
  Run last;
  for (int i = 0; i < repeat; ++i) {
    last = run_once(acommsctl, c.env, format, output);
    if (last.status != 0) {
      std::printf("%-18s acommsctl exited with %d\n", c.name, last.status);
      std::remove(output.c_str());
      return 1;
    }
    seconds.push_back(last.seconds);
    cpu.push_back(last.cpu_seconds);
  }
  std::remove(output.c_str());
  std::sort(seconds.begin(), seconds.end());
  std::sort(cpu.begin(), cpu.end());
  const double median = seconds[seconds.size() / 2];
  std::printf("%-18s %-3s 2 threads  median %8.4f s  (min %.4f, max %.4f, %d runs)  CPU median %.4f s  %9.1f kB out"
              "   goal %.3f s  %s\n",
              c.name, format.empty() ? "csv" : format.c_str(), median, seconds.front(), seconds.back(), repeat,
              cpu[cpu.size() / 2], last.output_bytes / 1024.0, c.goal_s, median <= c.goal_s ? "met" : "NOT met");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  bool smoke = false;
  std::string only, format, acommsctl = ACOMMSCTL_BINARY;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--smoke") == 0) smoke = true;
    else if (std::strncmp(argv[i], "--repeat=", 9) == 0) repeat = std::max(1, std::atoi(argv[i] + 9));
    else if (std::strncmp(argv[i], "--case=", 7) == 0) only = argv[i] + 7;
    else if (std::strncmp(argv[i], "--format=", 9) == 0) format = argv[i] + 9;
    else if (std::strncmp(argv[i], "--acommsctl=", 12) == 0) acommsctl = argv[i] + 12;
    else {
      std::fprintf(stderr,
                   "usage: gram_cli_bench [--repeat=N] [--format=csv|shd] [--case=NAME] [--acommsctl=PATH] [--smoke]\n");
      return 2;
    }
  }
  const std::string conformance = std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/";
  const std::vector<Case> cases = {
      {"bench_munk_field", conformance + "bench_munk_field.env", 0.49},
      {"bench_shallow_25k", conformance + "bench_shallow_25k.env", 0.53},
      {"bench_munk_query", conformance + "bench_munk_query.env", 0.014},
      {"bench_lloyd_field", std::string(ACOMMS_BENCH_ENVS) + "/bench_lloyd_field.env", 0.114},
  };
  if (smoke) return bench(cases[2], acommsctl, format, 1);
  int failures = 0;
  bool found = only.empty();
  for (const Case& c : cases)
    if (only.empty() || only == c.name) {
      found = true;
      failures += bench(c, acommsctl, format, repeat);
    }
  if (!found) {
    std::fprintf(stderr, "gram_cli_bench: no case named %s\n", only.c_str());
    return 2;
  }
  return failures == 0 ? 0 : 1;
}
