#pragma once
// Where the simulator's model runs come from: off the core thread, back on it.
//
// Problem: a TL grid at 25 kHz takes the model seconds (thousands of beams);
// run on the core thread it would stall every MAC slot and queue of the
// node. Decision: the sim driver never runs the model itself. It hands an
// environment (source depth and receivers set) to a TlGridSource, keeps
// using the last grid it has, and takes the new one when the source calls
// back — always on the core thread, so the driver's state stays lock-free.
// The source behind the seam: ExecutorTlGridSource with two executors, one
// that runs work off the core thread (WorkerThread, for programs without the
// daemon; acommsd uses PoolTlGridSource, pool_tl_grid_source.h) and one that posts back to the
// core thread (asio::post on its io_context). Tests put a stand-in they can
// block in either place.
// Thread rules: request() on the core thread only; `done` runs on the core
// thread, never inside request().

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "acomms/gram/environment.pb.h"
#include "gram/transmission_loss.h"

namespace acomms::drivers {

struct ModelRun {
  enum class Kind { kTransmissionLoss, kDelaySpread };
  Kind kind = Kind::kTransmissionLoss;
  // For kDelaySpread: one irregular receiver; the RMS delay spread (spec
  // §5.2, 60 dB floor) of its arrivals.
  gram::Environment environment;
};

struct ModelAnswer {
  std::shared_ptr<const gram::TransmissionLoss> tl;  // kTransmissionLoss
  std::optional<double> delay_spread_s;              // kDelaySpread, when any path arrives
  std::string error;                                 // non-empty: the model refused or failed
};

class TlGridSource {
 public:
  using Done = std::function<void(ModelAnswer answer)>;
  virtual ~TlGridSource() = default;
  // Core thread only. Runs `run` off the core thread; `done` later runs on
  // the core thread with the answer (also with an error: never silently).
  virtual void request(ModelRun run, Done done) = 0;
};

// Runs the model (compute_transmission_loss / compute_arrivals); any thread.
ModelAnswer run_model(const ModelRun& run);

// The seam: `worker` runs a task off the core thread (e.g. WorkerThread),
// `to_core` runs a task on the core thread later.
class ExecutorTlGridSource final : public TlGridSource {
 public:
  using Executor = std::function<void(std::function<void()> task)>;
  ExecutorTlGridSource(Executor worker, Executor to_core);
  void request(ModelRun run, Done done) override;

 private:
  Executor worker_, to_core_;
};

// One thread that runs tasks in order, idle (blocked, no CPU) when there
// are none: the sim driver's worker when no GRAM pool is given. The
// destructor drops tasks not yet begun and waits for the running one.
class WorkerThread {
 public:
  WorkerThread();
  ~WorkerThread();
  WorkerThread(const WorkerThread&) = delete;
  WorkerThread& operator=(const WorkerThread&) = delete;
  void post(std::function<void()> task);

 private:
  void loop();
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> tasks_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace acomms::drivers
