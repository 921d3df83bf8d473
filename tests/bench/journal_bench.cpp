// Durable appends per second through SqliteJournal (group commit, WAL,
// synchronous=FULL), with 1, 8, 64 and 256 appender threads, each calling
// append() in a loop: every append is answered only once its batch is on
// disk. Goal (issue: durable queue): 50,000 durable submits/s with grouped
// commits.
//
// Also measures what bounds it: the cost of one fdatasync on the data dir's
// filesystem, and, from the writer's counters, the time per batch spent in
// COMMIT (the fsync) against the time per request spent outside it (CPU).
// With batch size B, commit time C and per-request cost r:
//     appends/s ~ B / (C + B * r)  ->  1 / r  as B grows.
//
//   build/tests/bench/journal_bench [--seconds=2] [--threads=1,8,64,256] [--dir=/tmp]
//   build/tests/bench/journal_bench --smoke      (what ctest runs: seconds, not figures)

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <spdlog/spdlog.h>

#include "count_list.h"
#include "fdatasync_probe.h"
#include "queue/sqlite_journal.h"
#include "store/group_commit_writer.h"
#include "store/store.h"

namespace {

namespace fs = std::filesystem;
using namespace acomms;
using Clock = std::chrono::steady_clock;

struct Options {
  double seconds = 2.0;
  std::vector<int> threads = {1, 8, 64, 256};
  std::string base_dir = fs::temp_directory_path().string();
  int fsyncs = 200;
};

struct Result {
  int threads = 0;
  uint64_t appends = 0;
  double seconds = 0;
  store::GroupCommitWriter::Stats stats;
};

Result run(const Options& options, int threads) {
  std::string dir = options.base_dir + "/acomms_journal_bench_" + std::to_string(::getpid()) +
                    "_" + std::to_string(threads);
  fs::remove_all(dir);
  Result result;
  result.threads = threads;
  {
    store::Store store(dir);
    store::GroupCommitWriter writer(store.db());
    queue::SqliteJournal journal(writer);
    // A typical small DCCL message: tens of bytes.
    queue::JournalMessage message;
    message.type = "goby.acomms.protobuf.NavigationReport";
    message.payload = std::string(32, '\x5a');
    message.src = 1;
    message.dest = 2;
    message.submitted_at = 1'700'000'000;

    std::atomic<bool> go{false}, stop{false};
    std::atomic<uint64_t> appends{0};
    std::vector<std::thread> appenders;
    for (int t = 0; t < threads; ++t) {
      appenders.emplace_back([&] {
        while (!go.load()) std::this_thread::yield();
        uint64_t mine = 0;
        while (!stop.load(std::memory_order_relaxed)) {
          journal.append(message);
          ++mine;
        }
        appends += mine;
      });
    }
    store::GroupCommitWriter::Stats before = writer.stats();
    auto start = Clock::now();
    go = true;
    std::this_thread::sleep_for(std::chrono::duration<double>(options.seconds));
    stop = true;
    for (auto& appender : appenders) appender.join();
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    result.appends = appends.load();
    store::GroupCommitWriter::Stats after = writer.stats();
    result.stats = after;
    result.stats.batches -= before.batches;
    result.stats.committed -= before.committed;
    result.stats.commit_seconds -= before.commit_seconds;
    result.stats.busy_seconds -= before.busy_seconds;
  }
  fs::remove_all(dir);
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--smoke") {
      options.seconds = 0.05;
      options.threads = {1, 8};
      options.fsyncs = 5;
    } else if (arg.rfind("--seconds=", 0) == 0) {
      options.seconds = std::stod(arg.substr(10));
    } else if (arg.rfind("--threads=", 0) == 0) {
      options.threads = bench::parse_count_list(arg.substr(10));
    } else if (arg.rfind("--dir=", 0) == 0) {
      options.base_dir = arg.substr(6);
    } else {
      std::fprintf(stderr,
                   "usage: journal_bench [--seconds=S] [--threads=1,8,64,256] [--dir=D] [--smoke]\n");
      return 2;
    }
  }
  spdlog::set_level(spdlog::level::warn);

  double in_place = 0;
  double extending = 0;
  try {
    in_place = bench::fdatasync_seconds(options.base_dir, options.fsyncs, false);
    extending = bench::fdatasync_seconds(options.base_dir, options.fsyncs, true);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "journal_bench: %s\n", e.what());
    return 1;
  }
  std::printf("%s: 4 KiB write + fdatasync: %.3f ms in place, %.3f ms extending the file "
              "(ceilings %.0f and %.0f commits/s)\n",
              options.base_dir.c_str(), in_place * 1e3, extending * 1e3, 1 / in_place,
              1 / extending);
  std::printf("%8s %10s %12s %10s %10s %12s %14s\n", "threads", "appends", "appends/s",
              "mean_batch", "max_batch", "commit_ms", "cpu_us/append");
  for (int threads : options.threads) {
    Result r = run(options, threads);
    const auto& s = r.stats;
    double mean_batch = s.batches ? static_cast<double>(s.committed) / s.batches : 0;
    double commit_ms = s.batches ? s.commit_seconds / s.batches * 1e3 : 0;
    double cpu_us = s.committed ? (s.busy_seconds - s.commit_seconds) / s.committed * 1e6 : 0;
    std::printf("%8d %10llu %12.0f %10.1f %10llu %12.3f %14.2f\n", r.threads,
                static_cast<unsigned long long>(r.appends), r.appends / r.seconds, mean_batch,
                static_cast<unsigned long long>(s.max_batch), commit_ms, cpu_us);
    std::fflush(stdout);
  }
  return 0;
}
