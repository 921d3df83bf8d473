// The worker pool (see model_pool.h).
#include "gram/model_pool.h"

#include <algorithm>
#include <atomic>
#include <cstring>

#include "gram/depth_objective_proto.h"
#include "gram/environment_validation.h"

namespace acomms::gram {

struct ModelTicket::Job {
  Job(ModelRequest r, std::string c, ModelPool::Done d)
      : request(std::move(r)), consumer(std::move(c)), done(std::move(d)), token(request.deadline) {}
  ModelRequest request;
  std::string consumer;
  ModelPool::Done done;
  CancelToken token;
  DepthObjectiveRequest objective;  // request.objective, converted
  std::string key;                  // the cache key
  std::atomic<bool> answered{false};

  // Calls `done` unless another thread already did: a cancel may race the
  // worker's answer.
  void answer(ModelOutcome outcome) {
    if (answered.exchange(true)) return;
    ModelPool::Done d = std::move(done);
    d(std::move(outcome));
  }
  ModelStatus stop_status() const {
    return token.deadline_passed() ? ModelStatus::kDeadlineExceeded : ModelStatus::kCancelled;
  }
};

namespace {

const char* kind_name(ModelKind kind) {
  switch (kind) {
    case ModelKind::kTransmissionLoss: return "transmission loss";
    case ModelKind::kArrivals: return "arrivals";
    case ModelKind::kDepthObjective: return "depth objective";
  }
  return "model";
}

void append_size(std::string& key, std::size_t n) {
  char bytes[sizeof n];
  std::memcpy(bytes, &n, sizeof n);
  key.append(bytes, sizeof n);
}

// Every input that changes the answer, length-prefixed so that no two
// requests share bytes.
std::string cache_key(const ModelRequest& request, const std::string& engine) {
  std::string key;
  key.push_back(static_cast<char>(request.kind));
  append_size(key, engine.size());
  key += engine;
  append_size(key, request.environments.size());
  for (const Environment& env : request.environments) {
    std::string bytes = env.SerializeAsString();
    append_size(key, bytes.size());
    key += bytes;
  }
  if (request.kind == ModelKind::kArrivals) append_size(key, request.max_arrivals);
  if (request.kind == ModelKind::kDepthObjective) key += request.objective.SerializeAsString();
  return key;
}

std::size_t result_bytes(const ModelResult& r) {
  std::size_t bytes = sizeof r;
  for (const auto& tl : r.tl) bytes += 8 * (tl.range_m.size() + tl.depth_m.size() + tl.tl_db.size());
  for (const auto& a : r.arrivals) bytes += sizeof a + sizeof(Arrival) * a.arrivals.size();
  if (r.objective) bytes += 8 * 12 * r.objective->depth_m.size();
  return bytes;
}

// Validates on the caller's thread (cheap beside a run); the message names
// the field. For several instances, also which one.
std::optional<std::string> validate(const ModelRequest& request, DepthObjectiveRequest* objective) {
  const std::size_t n = request.environments.size();
  if (n == 0) return "no environment to run";
  if (request.kind != ModelKind::kDepthObjective && n != 1)
    return std::string(kind_name(request.kind)) + " takes exactly one environment, not " + std::to_string(n);
  for (std::size_t i = 0; i < n; ++i)
    if (auto error = validate_environment(request.environments[i]))
      return n == 1 ? *error : "instance " + std::to_string(i) + ": " + *error;
  if (request.kind == ModelKind::kArrivals && request.max_arrivals == 0) return "max_arrivals must be at least 1";
  if (request.kind == ModelKind::kDepthObjective) {
    try {
      *objective = request_from_proto(request.objective);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    if (auto error = validate_depth_objective_request(*objective)) return error;
  }
  return std::nullopt;
}

}  // namespace

void ModelTicket::cancel() {
  job_->token.cancel();
  pool_->withdraw(job_);
}

ModelPool::ModelPool(ModelPoolOptions options, std::unique_ptr<ModelEngine> engine)
    : options_(options), engine_(std::move(engine)), engine_name_(engine_->name()), cache_(options.cache_bytes) {
  options_.workers = std::max(1u, options_.workers);
  for (unsigned i = 0; i < options_.workers; ++i) workers_.emplace_back([this] { work(); });
}

ModelPool::~ModelPool() {
  std::deque<std::shared_ptr<Job>> waiting;
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    waiting.swap(waiting_);
    for (auto& job : active_) job->token.cancel();
  }
  wake_.notify_all();
  for (auto& job : waiting) job->answer({ModelStatus::kShuttingDown, "the daemon is stopping", nullptr, false});
  for (auto& worker : workers_) worker.join();
}

std::shared_ptr<ModelTicket> ModelPool::submit(ModelRequest request, std::string consumer, Done done) {
  auto job = std::make_shared<Job>(std::move(request), std::move(consumer), std::move(done));
  auto ticket = std::shared_ptr<ModelTicket>(new ModelTicket(this, job));
  if (auto error = validate(job->request, &job->objective)) {
    job->answer({ModelStatus::kInvalid, *error, nullptr, false});
    return ticket;
  }
  job->key = cache_key(job->request, engine_name_);
  std::shared_ptr<Job> superseded;
  ModelOutcome immediate;
  bool answered_now = false;
  {
    std::lock_guard lock(mutex_);
    if (stopping_) {
      immediate = {ModelStatus::kShuttingDown, "the daemon is stopping", nullptr, false};
      answered_now = true;
    } else if (auto hit = cache_.find(job->key)) {
      ++cache_hits_;
      immediate = {ModelStatus::kOk, "", std::move(hit), true};
      answered_now = true;
    } else {
      if (!job->consumer.empty()) {
        auto same = std::find_if(waiting_.begin(), waiting_.end(),
                                 [&](const auto& w) { return w->consumer == job->consumer; });
        if (same != waiting_.end()) {
          superseded = *same;
          waiting_.erase(same);
        }
      }
      if (waiting_.size() >= options_.queue_limit) {
        immediate = {ModelStatus::kQueueFull,
                     "gram.queue_limit = " + std::to_string(options_.queue_limit) +
                         " requests are already waiting for a model worker; try again later",
                     nullptr, false};
        answered_now = true;
      } else {
        waiting_.push_back(job);
      }
    }
  }
  if (superseded)
    superseded->answer({ModelStatus::kSuperseded,
                        "superseded by a newer request of consumer \"" + job->consumer + "\"", nullptr, false});
  if (answered_now) job->answer(std::move(immediate));
  else wake_.notify_one();
  return ticket;
}

void ModelPool::withdraw(const std::shared_ptr<Job>& job) {
  {
    std::lock_guard lock(mutex_);
    auto it = std::find(waiting_.begin(), waiting_.end(), job);
    if (it == waiting_.end()) return;  // running (its token stops it) or done
    waiting_.erase(it);
  }
  job->answer({job->stop_status(), "", nullptr, false});
}

void ModelPool::pause() {
  std::lock_guard lock(mutex_);
  paused_ = true;
}

void ModelPool::resume() {
  {
    std::lock_guard lock(mutex_);
    paused_ = false;
  }
  wake_.notify_all();
}

ModelPoolStats ModelPool::stats() const {
  std::lock_guard lock(mutex_);
  ModelPoolStats s;
  s.workers = options_.workers;
  s.running = running_;
  s.waiting = waiting_.size();
  s.cache_entries = cache_.entries();
  s.cache_bytes = cache_.bytes();
  s.cache_hits = cache_hits_;
  s.completed = completed_;
  return s;
}

void ModelPool::work() {
  for (;;) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || (!paused_ && !waiting_.empty()); });
      if (stopping_) return;
      job = waiting_.front();
      waiting_.pop_front();
      ++running_;
      active_.push_back(job);
    }
    run(*job);
    std::lock_guard lock(mutex_);
    --running_;
    ++completed_;
    active_.erase(std::find(active_.begin(), active_.end(), job));
  }
}

ModelResult ModelPool::compute(const Job& job) {
  const ModelRequest& request = job.request;
  ModelResult result;
  result.engine = engine_name_;
  switch (request.kind) {
    case ModelKind::kTransmissionLoss:
      result.tl.push_back(engine_->transmission_loss(request.environments[0], job.token));
      break;
    case ModelKind::kArrivals: {
      ArrivalOptions options;
      options.max_arrivals = request.max_arrivals;
      options.cancel = &job.token;
      result.arrivals = compute_arrivals(request.environments[0], options);
      result.engine = "builtin";
      break;
    }
    case ModelKind::kDepthObjective:
      // Each instance's TL is cached as a TransmissionLoss answer of its own:
      // the vehicle's next query (new range, speed or heading, same
      // environment) then costs no model run.
      for (const Environment& env : request.environments) {
        ModelRequest tl_request;
        tl_request.environments = {env};
        const std::string key = cache_key(tl_request, engine_name_);
        std::shared_ptr<const ModelResult> cached;
        {
          std::lock_guard lock(mutex_);
          cached = cache_.find(key);
        }
        if (cached) {
          result.tl.push_back(cached->tl.at(0));
          continue;
        }
        auto single = std::make_shared<ModelResult>();
        single->engine = engine_name_;
        single->tl.push_back(engine_->transmission_loss(env, job.token));
        result.tl.push_back(single->tl[0]);
        std::lock_guard lock(mutex_);
        cache_.insert(key, single, result_bytes(*single));
      }
      result.objective = compute_depth_objective(result.tl, request.environments[0], job.objective);
      break;
  }
  return result;
}

void ModelPool::run(Job& job) {
  if (job.token.cancelled()) {
    job.answer({job.stop_status(), "", nullptr, false});
    return;
  }
  ModelOutcome outcome;
  try {
    auto result = std::make_shared<const ModelResult>(compute(job));
    {
      std::lock_guard lock(mutex_);
      cache_.insert(job.key, result, result_bytes(*result));
    }
    outcome = {ModelStatus::kOk, "", std::move(result), false};
  } catch (const ModelCancelled&) {
    outcome = {job.stop_status(), "", nullptr, false};
  } catch (const std::invalid_argument& e) {
    outcome = {ModelStatus::kInvalid, e.what(), nullptr, false};
  } catch (const EngineError& e) {
    outcome = {ModelStatus::kEngineFailed, e.what(), nullptr, false};
  } catch (const std::exception& e) {
    outcome = {ModelStatus::kEngineFailed, std::string(kind_name(job.request.kind)) + " failed: " + e.what(), nullptr,
               false};
  }
  job.answer(std::move(outcome));
}

}  // namespace acomms::gram
