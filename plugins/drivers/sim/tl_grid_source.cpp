#include "sim/tl_grid_source.h"

#include <exception>

#include "core/core_thread.h"
#include "gram/arrivals.h"

namespace acomms::drivers {

ModelAnswer run_model(const ModelRun& run) {
  ModelAnswer answer;
  try {
    if (run.kind == ModelRun::Kind::kTransmissionLoss) {
      // One thread: the pool (or WorkerThread) is the parallelism; a model
      // that took every core would starve the node it simulates.
      answer.tl = std::make_shared<const gram::TransmissionLoss>(
          gram::compute_transmission_loss(run.environment, {1}));
    } else {
      const auto arrivals = gram::compute_arrivals(run.environment);
      if (!arrivals.empty() && !arrivals[0].arrivals.empty())
        answer.delay_spread_s = gram::rms_delay_spread(arrivals[0].arrivals, 60.0).tau_rms_s;
    }
  } catch (const std::exception& e) {
    answer.error = e.what();
  }
  return answer;
}

ExecutorTlGridSource::ExecutorTlGridSource(Executor worker, Executor to_core)
    : worker_(std::move(worker)), to_core_(std::move(to_core)) {}

void ExecutorTlGridSource::request(ModelRun run, Done done) {
  ACOMMS_ASSERT_CORE_THREAD();
  worker_([run = std::move(run), done = std::move(done), to_core = to_core_]() mutable {
    auto answer = std::make_shared<ModelAnswer>(run_model(run));
    to_core([answer, done = std::move(done)] { done(std::move(*answer)); });
  });
}

WorkerThread::WorkerThread() : thread_([this] { loop(); }) {}

WorkerThread::~WorkerThread() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    tasks_.clear();
  }
  wake_.notify_one();
  thread_.join();
}

void WorkerThread::post(std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    tasks_.push_back(std::move(task));
  }
  wake_.notify_one();
}

void WorkerThread::loop() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !tasks_.empty(); });
      if (stopping_) return;
      task = std::move(tasks_.front());
      tasks_.pop_front();
    }
    task();
  }
}

}  // namespace acomms::drivers
