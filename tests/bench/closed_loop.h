// A closed-loop load: `in_flight` requests outstanding at all times until
// `requests` are answered, each timed from issue to answer; requests per
// second and the latency percentiles. The GRAM pool and service benches
// drive the same loop, one in process and one over gRPC.
#pragma once

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <vector>

namespace acomms::bench {

struct ClosedLoopFigures {
  double per_second = 0, p50_ms = 0, p99_ms = 0;
  int failed = 0;
};

// `issue(i, done)` starts request i (0, 1, ...) and arranges for done(ok)
// to be called once, on any thread, when it is answered. It is called
// without the loop's lock held: done may run inside it (an answer from a
// cache, or gRPC answering on the calling thread).
using Issue = std::function<void(int index, std::function<void(bool ok)> done)>;

inline ClosedLoopFigures run_closed_loop(int requests, int in_flight, const Issue& issue) {
  using Clock = std::chrono::steady_clock;
  std::mutex m;
  std::condition_variable cv;
  std::vector<double> latency_ms;
  int submitted = 0, answered = 0, failed = 0;
  const auto start = Clock::now();
  std::unique_lock lock(m);
  while (answered < requests) {
    while (submitted < requests && submitted - answered < in_flight) {
      const int index = submitted++;
      lock.unlock();
      const auto issued = Clock::now();
      issue(index, [&, issued](bool ok) {
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - issued).count();
        std::lock_guard answered_lock(m);
        latency_ms.push_back(ms);
        if (!ok) ++failed;
        ++answered;
        cv.notify_all();
      });
      lock.lock();
    }
    cv.wait(lock, [&] { return answered == requests || (submitted < requests && submitted - answered < in_flight); });
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::sort(latency_ms.begin(), latency_ms.end());
  auto at = [&](double q) {
    return latency_ms[std::min(latency_ms.size() - 1, static_cast<std::size_t>(q * latency_ms.size()))];
  };
  return {requests / seconds, at(0.5), at(0.99), failed};
}

}  // namespace acomms::bench
