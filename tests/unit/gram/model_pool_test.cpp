// The worker pool's promises (gram/model_pool.h), shown without timing:
// a gated stand-in engine holds a run until the test opens the gate, and
// pause() holds every worker, so "waiting" and "running" are states the
// test makes, not moments it hopes to catch.
#include <gtest/gtest.h>
#include <sys/types.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <future>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "gram/bellhop_import.h"
#include "gram/model_pool.h"

namespace acomms::gram {
namespace {

using namespace std::chrono_literals;

Environment small_env(double source_depth = 20) {
  Environment env =
      import_bellhop_env_file(std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/envs/pekeris_lossy_500hz.env")
          .environment;
  env.clear_receiver_range_m();
  for (int i = 0; i <= 10; ++i) env.add_receiver_range_m(200.0 * i);
  env.set_beam_count(200);
  env.set_box_range_m(2100);
  env.set_source_depth_m(source_depth);
  return env;
}

// Answers TL = source depth everywhere, once the gate is open; stops when
// its token fires. Counts its runs.
class GatedEngine final : public ModelEngine {
 public:
  std::string name() const override { return "gated"; }
  TransmissionLoss transmission_loss(const Environment& env, const CancelToken& cancel) override {
    std::unique_lock lock(mutex_);
    ++started_;
    started_cv_.notify_all();
    while (!open_) {
      if (cancel.cancelled()) throw ModelCancelled();
      gate_.wait_for(lock, 5ms);
    }
    ++runs_;
    TransmissionLoss tl;
    tl.range_m.assign(env.receiver_range_m().begin(), env.receiver_range_m().end());
    tl.depth_m.assign(env.receiver_depth_m().begin(), env.receiver_depth_m().end());
    tl.tl_db.assign(tl.range_m.size() * tl.depth_m.size(), env.source_depth_m());
    return tl;
  }
  void open() {
    std::lock_guard lock(mutex_);
    open_ = true;
    gate_.notify_all();
  }
  void wait_started(int n) {
    std::unique_lock lock(mutex_);
    started_cv_.wait(lock, [&] { return started_ >= n; });
  }
  int runs() {
    std::lock_guard lock(mutex_);
    return runs_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable gate_, started_cv_;
  bool open_ = false;
  int started_ = 0, runs_ = 0;
};

struct Answer {
  std::promise<ModelOutcome> promise;
  std::future<ModelOutcome> future = promise.get_future();
  ModelPool::Done done() {
    return [this](ModelOutcome o) { promise.set_value(std::move(o)); };
  }
  ModelOutcome get() { return future.get(); }
  bool ready() { return future.wait_for(0s) == std::future_status::ready; }
};

ModelRequest tl_request(double source_depth = 20) {
  ModelRequest r;
  r.environments.push_back(small_env(source_depth));
  return r;
}

TEST(GramModelPool, AConsumersNewerRequestSupersedesItsWaitingOne) {
  auto engine = std::make_unique<GatedEngine>();
  GatedEngine* gate = engine.get();
  ModelPool pool({1, 16, 1 << 20}, std::move(engine));
  pool.pause();
  Answer first, second, other;
  pool.submit(tl_request(10), "behaviour", first.done());
  pool.submit(tl_request(11), "other", other.done());
  pool.submit(tl_request(12), "behaviour", second.done());
  ModelOutcome superseded = first.get();
  EXPECT_EQ(superseded.status, ModelStatus::kSuperseded);
  EXPECT_NE(superseded.message.find("\"behaviour\""), std::string::npos) << superseded.message;
  EXPECT_EQ(pool.stats().waiting, 2u);
  gate->open();
  pool.resume();
  EXPECT_EQ(second.get().result->tl[0].tl_db[0], 12.0);
  EXPECT_EQ(other.get().status, ModelStatus::kOk);
  EXPECT_EQ(gate->runs(), 2);
}

TEST(GramModelPool, ARunningRequestIsNotSuperseded) {
  auto engine = std::make_unique<GatedEngine>();
  GatedEngine* gate = engine.get();
  ModelPool pool({1, 16, 1 << 20}, std::move(engine));
  Answer running, newer;
  pool.submit(tl_request(10), "behaviour", running.done());
  gate->wait_started(1);
  pool.submit(tl_request(12), "behaviour", newer.done());
  gate->open();
  EXPECT_EQ(running.get().status, ModelStatus::kOk);
  EXPECT_EQ(newer.get().status, ModelStatus::kOk);
}

TEST(GramModelPool, AFullQueueRefusesAtOnceNamingTheLimit) {
  ModelPool pool({1, 2, 1 << 20}, std::make_unique<GatedEngine>());
  pool.pause();
  Answer a, b, c;
  pool.submit(tl_request(10), "", a.done());
  pool.submit(tl_request(11), "", b.done());
  pool.submit(tl_request(12), "", c.done());
  ASSERT_TRUE(c.ready());
  ModelOutcome full = c.get();
  EXPECT_EQ(full.status, ModelStatus::kQueueFull);
  EXPECT_NE(full.message.find("queue_limit = 2"), std::string::npos) << full.message;
  EXPECT_FALSE(a.ready());
}

TEST(GramModelPool, CancelStopsARunningModelAndFreesTheWorker) {
  auto engine = std::make_unique<GatedEngine>();
  GatedEngine* gate = engine.get();
  ModelPool pool({1, 16, 1 << 20}, std::move(engine));
  Answer running, next;
  auto ticket = pool.submit(tl_request(10), "", running.done());
  gate->wait_started(1);
  EXPECT_EQ(pool.stats().running, 1u);
  ticket->cancel();
  EXPECT_EQ(running.get().status, ModelStatus::kCancelled);
  // The worker is free again: the next request runs on it.
  pool.submit(tl_request(11), "", next.done());
  gate->wait_started(2);
  gate->open();
  EXPECT_EQ(next.get().status, ModelStatus::kOk);
}

TEST(GramModelPool, CancelAnswersAWaitingRequestWithoutRunningIt) {
  auto engine = std::make_unique<GatedEngine>();
  GatedEngine* gate = engine.get();
  ModelPool pool({1, 16, 1 << 20}, std::move(engine));
  pool.pause();
  Answer waiting;
  auto ticket = pool.submit(tl_request(10), "", waiting.done());
  ticket->cancel();
  EXPECT_EQ(waiting.get().status, ModelStatus::kCancelled);
  EXPECT_EQ(pool.stats().waiting, 0u);
  gate->open();
  pool.resume();
  EXPECT_EQ(gate->runs(), 0);
}

TEST(GramModelPool, ADeadlineStopsTheBuiltInModelMidRun) {
  ModelPool pool({1, 16, 1 << 20}, make_builtin_engine());
  ModelRequest request = tl_request();
  request.environments[0].set_beam_count(100000);  // far longer than the deadline
  request.environments[0].clear_receiver_range_m();
  for (int i = 0; i <= 2000; ++i) request.environments[0].add_receiver_range_m(i);
  request.deadline = CancelToken::Clock::now() + 50ms;
  Answer answer;
  pool.submit(request, "", answer.done());
  EXPECT_EQ(answer.get().status, ModelStatus::kDeadlineExceeded);
}

TEST(GramModelPool, AnIdenticalRequestIsAnsweredFromTheCache) {
  ModelPool pool({1, 16, 1 << 20}, make_builtin_engine());
  Answer cold, warm, different;
  pool.submit(tl_request(20), "", cold.done());
  ModelOutcome first = cold.get();
  ASSERT_EQ(first.status, ModelStatus::kOk) << first.message;
  EXPECT_FALSE(first.from_cache);
  pool.submit(tl_request(20), "", warm.done());
  ASSERT_TRUE(warm.ready());  // answered on the submitting thread
  ModelOutcome second = warm.get();
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(second.result, first.result);
  pool.submit(tl_request(21), "", different.done());
  EXPECT_FALSE(different.get().from_cache);
  EXPECT_EQ(pool.stats().cache_hits, 1u);
}

TEST(GramModelPool, ADepthObjectiveReusesEachInstancesCachedTl) {
  auto engine = std::make_unique<GatedEngine>();
  GatedEngine* gate = engine.get();
  gate->open();
  ModelPool pool({1, 16, 1 << 20}, std::move(engine));
  ModelRequest request;
  request.kind = ModelKind::kDepthObjective;
  request.environments = {small_env(10), small_env(12)};
  auto& q = request.objective;
  q.set_range_m(1000);
  q.set_speed_mps(1.5);
  q.set_horizon_s(120);
  q.set_h_max_db(108);
  q.mutable_limits()->set_max_depth_m(90);
  Answer first, second;
  pool.submit(request, "", first.done());
  ModelOutcome a = first.get();
  ASSERT_EQ(a.status, ModelStatus::kOk) << a.message;
  EXPECT_EQ(gate->runs(), 2);
  q.set_speed_mps(2.5);  // another query, the same environments
  pool.submit(request, "", second.done());
  ModelOutcome b = second.get();
  ASSERT_EQ(b.status, ModelStatus::kOk) << b.message;
  EXPECT_FALSE(b.from_cache);
  EXPECT_EQ(gate->runs(), 2);  // no model run
  // TL 10 and 12 dB everywhere: eq. 4.4 of the two.
  EXPECT_NEAR(b.result->objective->h_bar_db[0], -10 * std::log10((std::pow(10, -1.0) + std::pow(10, -1.2)) / 2), 1e-9);
}

TEST(GramModelPool, TheCacheStaysWithinItsBudget) {
  auto engine = std::make_unique<GatedEngine>();
  engine->open();
  ModelPool pool({1, 16, 3000}, std::move(engine));
  // Each answer is a few hundred bytes plus its key (the environment).
  for (int i = 0; i < 20; ++i) {
    Answer a;
    pool.submit(tl_request(10 + i), "", a.done());
    a.get();
  }
  EXPECT_LE(pool.stats().cache_bytes, 3000u);
}

TEST(GramModelPool, ABadEnvironmentIsRefusedNamingTheField) {
  ModelPool pool({1, 16, 1 << 20}, make_builtin_engine());
  ModelRequest request = tl_request();
  request.environments[0].mutable_sound_speed(1)->set_depth_m(-5);
  Answer answer;
  pool.submit(request, "", answer.done());
  ModelOutcome o = answer.get();
  EXPECT_EQ(o.status, ModelStatus::kInvalid);
  EXPECT_NE(o.message.find("sound_speed[1].depth_m"), std::string::npos) << o.message;
}

// The threads of this process (/proc/self/task).
std::set<pid_t> thread_ids() {
  std::set<pid_t> ids;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task"))
    ids.insert(static_cast<pid_t>(std::stol(entry.path().filename().string())));
  return ids;
}

// What the kernel says of one thread: asleep or not, and how often it has
// been switched out (each wake-up of a sleeper ends in one more switch).
struct ThreadActivity {
  bool asleep = false;
  std::uint64_t switches = 0;
  bool operator==(const ThreadActivity&) const = default;
};

ThreadActivity activity(pid_t thread) {
  std::ifstream status("/proc/self/task/" + std::to_string(thread) + "/status");
  ThreadActivity a;
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("State:", 0) == 0) a.asleep = line.find("S (sleeping)") != std::string::npos;
    if (line.rfind("voluntary_ctxt_switches:", 0) == 0 || line.rfind("nonvoluntary_ctxt_switches:", 0) == 0)
      a.switches += std::stoull(line.substr(line.find(':') + 1));
  }
  return a;
}

std::vector<ThreadActivity> activity(const std::vector<pid_t>& threads) {
  std::vector<ThreadActivity> all;
  for (pid_t t : threads) all.push_back(activity(t));
  return all;
}

// Idle workers wait on a condition variable: once asleep, an idle worker is
// never woken (a worker that polled, even rarely, would be switched in and
// out again). Counted by the kernel's context switches of each worker
// thread, not by time: a slow machine only lengthens the quiet interval.
TEST(GramModelPool, IdleWorkersSleepUntilWorkArrives) {
  const std::set<pid_t> before = thread_ids();
  ModelPool pool({4, 16, 1 << 20}, make_builtin_engine());
  EXPECT_EQ(pool.stats().workers, 4u);
  std::vector<pid_t> workers;
  for (pid_t t : thread_ids())
    if (!before.contains(t)) workers.push_back(t);
  ASSERT_EQ(workers.size(), 4u);
  // Started: every worker asleep, and no switch between two looks.
  std::vector<ThreadActivity> settled = activity(workers);
  bool started = false;
  for (int look = 0; look < 1000 && !started; ++look) {
    std::this_thread::sleep_for(10ms);
    std::vector<ThreadActivity> now = activity(workers);
    started = now == settled && std::all_of(now.begin(), now.end(), [](const auto& a) { return a.asleep; });
    settled = now;
  }
  ASSERT_TRUE(started) << "the workers never went to sleep";

  std::this_thread::sleep_for(300ms);  // a quiet interval: no request, so no wake-up
  EXPECT_EQ(activity(workers), settled) << "an idle worker was woken";

  // And the count does see a wake-up: work wakes a worker.
  Answer answer;
  pool.submit(tl_request(), "", answer.done());
  ASSERT_EQ(answer.get().status, ModelStatus::kOk);
  std::uint64_t switches_before = 0, switches_after = 0;
  for (const auto& a : settled) switches_before += a.switches;
  for (const auto& a : activity(workers)) switches_after += a.switches;
  EXPECT_GT(switches_after, switches_before);
}

TEST(GramModelPool, DestroyingThePoolAnswersWaitingRequests) {
  Answer waiting;
  {
    ModelPool pool({1, 16, 1 << 20}, std::make_unique<GatedEngine>());
    pool.pause();
    pool.submit(tl_request(), "", waiting.done());
  }
  EXPECT_EQ(waiting.get().status, ModelStatus::kShuttingDown);
}

}  // namespace
}  // namespace acomms::gram
