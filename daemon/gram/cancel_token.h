// A model run's way to learn that nobody wants its answer any more.
//
// Problem: a client's deadline or cancel must stop a running model within a
// fraction of a second, and a worker must not burn minutes on a result that
// will be thrown away. Decision: the run polls a token between beams (one
// relaxed atomic load and, with a deadline, one steady-clock read per beam:
// negligible beside a ray trace); a cancelled run throws ModelCancelled
// from its entry point, after its own threads have joined. The token is
// cancelled from any thread (the gRPC thread that saw the client go) and
// read from the model's threads. Thread-safe.
#pragma once

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>

namespace acomms::gram {

class CancelToken {
 public:
  using Clock = std::chrono::steady_clock;

  CancelToken() = default;
  explicit CancelToken(Clock::time_point deadline) : deadline_(deadline) {}

  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const {
    return cancelled_.load(std::memory_order_relaxed) || (deadline_ != Clock::time_point::max() && Clock::now() >= deadline_);
  }
  bool deadline_passed() const { return deadline_ != Clock::time_point::max() && Clock::now() >= deadline_; }
  Clock::time_point deadline() const { return deadline_; }

 private:
  std::atomic<bool> cancelled_{false};
  Clock::time_point deadline_ = Clock::time_point::max();
};

// Thrown by a model entry point whose token was cancelled mid-run.
class ModelCancelled : public std::runtime_error {
 public:
  ModelCancelled() : std::runtime_error("model run cancelled") {}
};

// Throws ModelCancelled when `token` (may be null) is cancelled.
inline void throw_if_cancelled(const CancelToken* token) {
  if (token && token->cancelled()) throw ModelCancelled();
}

}  // namespace acomms::gram
