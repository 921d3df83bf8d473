// The time of one event-log pruning step (daemon/queue/event_log_retention.h)
// in a store holding a million events: the step shares a group commit with
// Submits, so its time is what a Submit may wait behind it. Prints figures
// (each step timed with its commit, as the writer runs it); --smoke uses
// 20,000 events so ctest only checks that it runs.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "queue/event_log_retention.h"
#include "store/store.h"

namespace fs = std::filesystem;
using namespace acomms;

int main(int argc, char** argv) {
  const bool smoke = argc > 1 && std::strcmp(argv[1], "--smoke") == 0;
  const int64_t events = smoke ? 20'000 : 1'000'000;
  const fs::path dir = fs::temp_directory_path() / ("acomms-prune-bench-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  {
    store::Store store((dir / "data").string());
    store::Database& db = store.db();
    // A month of traffic, one event every 2.6 s, oldest first; every fifth a
    // received message with its bytes and seq, as the daemon writes them.
    const double start = 1'700'000'000;
    db.exec("BEGIN");
    store::Statement insert = db.prepare(
        "INSERT INTO event_log (time, kind, type, message_id, src, dest, detail, encoded, seq) "
        "VALUES (?, ?, 'example.Status', ?, 1, 2, '', ?, ?)");
    int64_t seq = 0;
    for (int64_t i = 0; i < events; ++i) {
      const bool received = i % 5 == 0;
      insert.bind_double(1, start + static_cast<double>(i) * 2.6)
          .bind(2, std::string_view(received ? "received" : "sent"));
      if (received) {
        insert.bind_null(3).bind_blob(4, std::string(24, 'b')).bind(5, ++seq);
      } else {
        insert.bind(3, i).bind_null(4).bind_null(5);
      }
      insert.step();
      insert.reset();
    }
    db.exec("COMMIT");
    const double now = start + static_cast<double>(events) * 2.6;

    queue::RetentionPolicy policy;
    policy.max_bytes = 0;
    policy.max_age_s = now - start - static_cast<double>(events) * 2.6 / 2;  // half the log is too old
    std::vector<double> ms;
    for (int step = 0; step < (smoke ? 5 : 40); ++step) {
      auto t0 = std::chrono::steady_clock::now();
      db.exec("BEGIN IMMEDIATE");
      size_t deleted = queue::prune_event_log_step(db, policy, now, now - 300);
      db.exec("COMMIT");
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      if (deleted != policy.rows_per_step) {
        std::fprintf(stderr, "step %d deleted %zu rows, expected %zu\n", step, deleted, policy.rows_per_step);
        return 1;
      }
    }
    // The size bound's step also measures the store's used pages.
    policy.max_age_s = 0;
    policy.max_bytes = 1;
    auto t0 = std::chrono::steady_clock::now();
    db.exec("BEGIN IMMEDIATE");
    queue::prune_event_log_step(db, policy, now, now - 300);
    db.exec("COMMIT");
    const double size_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::sort(ms.begin(), ms.end());
    std::printf("prune step (%zu rows, with its commit) in a log of %lld events: median %.2f ms, max %.2f ms; "
                "size-bound step %.2f ms\n",
                policy.rows_per_step, static_cast<long long>(events), ms[ms.size() / 2], ms.back(), size_ms);
  }
  fs::remove_all(dir);
  return 0;
}
