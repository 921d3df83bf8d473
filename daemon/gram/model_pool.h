// GRAM's worker pool: model runs off the gRPC and core threads (Schneider
// (2013) §4.2: a program asks asynchronously and keeps working with its last
// answer).
//
// The contract, for the gRPC service and for in-process callers (the
// simulator asks it for TL grids):
// - submit() never blocks and never runs a model on the caller's thread.
//   `done` is called exactly once, on a worker thread, or on the caller's
//   thread when the answer is known at once (invalid request, full queue,
//   cache hit, superseded), or on the thread that cancelled a waiting
//   request. `done` must be short and must not block; it is never called
//   with the pool's lock held, so it may submit again.
// - A request with a non-empty consumer key supersedes (kSuperseded) that
//   consumer's request still WAITING; a running one is left to finish.
// - More than queue_limit waiting requests: the new one gets kQueueFull.
// - Identical requests (same kind, environments, options, engine) are
//   answered from a cache bounded by cache_bytes, without a queue slot. A
//   depth objective also caches each instance's TL as a TL answer, so a
//   new query on the same environment runs no model.
// - A ticket's cancel(), or the request's deadline, stops a running model
//   between two beams (a fraction of a second) and frees the worker.
// - Idle workers wait on a condition variable: no CPU.
// Thread-safe. Tickets must not be used after the pool is destroyed; the
// destructor answers waiting requests kShuttingDown and cancels running
// ones before joining the workers.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "acomms/gram/depth_objective.pb.h"
#include "acomms/gram/environment.pb.h"
#include "gram/arrivals.h"
#include "gram/cancel_token.h"
#include "gram/depth_objective.h"
#include "gram/model_engine.h"
#include "gram/result_cache.h"
#include "gram/transmission_loss.h"

namespace acomms::gram {

enum class ModelKind { kTransmissionLoss, kArrivals, kDepthObjective };

struct ModelRequest {
  ModelKind kind = ModelKind::kTransmissionLoss;
  // TL and arrivals: exactly one. Depth objective: one per sound-speed
  // profile instance, all with the same receivers (eq. 4.4 averages them).
  std::vector<Environment> environments;
  std::size_t max_arrivals = 200;     // arrivals only
  DepthObjectiveQuery objective;      // depth objective only
  CancelToken::Clock::time_point deadline = CancelToken::Clock::time_point::max();
};

struct ModelResult {
  std::vector<TransmissionLoss> tl;        // TL: one; depth objective: one per instance
  std::vector<ReceiverArrivals> arrivals;  // arrivals only
  std::optional<DepthObjectiveResult> objective;
  std::string engine;                      // which engine computed the TL
};

enum class ModelStatus {
  kOk,
  kInvalid,           // the request breaks a rule (message names the field)
  kSuperseded,        // the consumer's newer request replaced it while waiting
  kQueueFull,
  kCancelled,         // the ticket was cancelled
  kDeadlineExceeded,  // the request's deadline passed
  kEngineFailed,      // the engine's own failure, its text verbatim
  kShuttingDown,
};

struct ModelOutcome {
  ModelStatus status = ModelStatus::kOk;
  std::string message;
  std::shared_ptr<const ModelResult> result;  // kOk only
  bool from_cache = false;
};

struct ModelPoolOptions {
  unsigned workers = 1;
  std::size_t queue_limit = 16;
  std::size_t cache_bytes = 64u << 20;
};

struct ModelPoolStats {
  unsigned workers = 0, running = 0;
  std::size_t waiting = 0, cache_entries = 0, cache_bytes = 0;
  std::uint64_t cache_hits = 0, completed = 0;
};

class ModelPool;

// A submitted request's handle: cancel() stops it waiting or running.
class ModelTicket {
 public:
  void cancel();

 private:
  friend class ModelPool;
  struct Job;
  ModelTicket(ModelPool* pool, std::shared_ptr<Job> job) : pool_(pool), job_(std::move(job)) {}
  ModelPool* pool_;
  std::shared_ptr<Job> job_;
};

class ModelPool {
 public:
  using Done = std::function<void(ModelOutcome)>;

  ModelPool(ModelPoolOptions options, std::unique_ptr<ModelEngine> engine);
  ~ModelPool();
  ModelPool(const ModelPool&) = delete;
  ModelPool& operator=(const ModelPool&) = delete;

  std::shared_ptr<ModelTicket> submit(ModelRequest request, std::string consumer, Done done);

  // For tests: while paused, workers start no new run (requests wait, so
  // supersede, full queue and cancel can be shown without timing).
  void pause();
  void resume();

  ModelPoolStats stats() const;
  const std::string& engine_name() const { return engine_name_; }

 private:
  friend class ModelTicket;
  using Job = ModelTicket::Job;

  void work();
  void run(Job& job);
  void withdraw(const std::shared_ptr<Job>& job);
  ModelResult compute(const Job& job);

  ModelPoolOptions options_;
  std::unique_ptr<ModelEngine> engine_;
  std::string engine_name_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::shared_ptr<Job>> waiting_;
  ResultCache cache_;
  bool paused_ = false;
  bool stopping_ = false;
  unsigned running_ = 0;
  std::uint64_t cache_hits_ = 0, completed_ = 0;
  std::vector<std::shared_ptr<Job>> active_;  // running, for the destructor to cancel
  std::vector<std::thread> workers_;
};

}  // namespace acomms::gram
