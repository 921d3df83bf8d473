// The simulator's model runs on GRAM's pool (sim/pool_tl_grid_source.h):
// the answer comes back through the core executor, never inside
// request(); the grid is the model's; the pool's refusals reach the
// physics as errors. The "core" here is a queue of tasks the test runs.
#include <gtest/gtest.h>

#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>

#include "gram/transmission_loss.h"
#include "sim/pool_tl_grid_source.h"

namespace acomms::drivers {
namespace {

gram::Environment small_env() {
  gram::Environment env;
  env.set_frequency_hz(2000);
  for (double z : {0.0, 100.0}) {
    auto* p = env.add_sound_speed();
    p->set_depth_m(z);
    p->set_speed_mps(1500);
  }
  env.set_source_depth_m(30);
  for (double z : {10.0, 50.0, 90.0}) env.add_receiver_depth_m(z);
  for (double r : {200.0, 400.0, 800.0}) env.add_receiver_range_m(r);
  env.set_launch_angle_min_deg(-60);
  env.set_launch_angle_max_deg(60);
  env.set_beam_count(200);
  env.set_box_depth_m(101);
  env.set_box_range_m(900);
  return env;
}

class Core {
 public:
  PoolTlGridSource::Executor executor() {
    return [this](std::function<void()> task) {
      std::lock_guard lock(mutex_);
      tasks_.push_back(std::move(task));
      posted_.notify_all();
    };
  }
  // Waits for the next posted task and runs it here.
  void run_one() {
    std::unique_lock lock(mutex_);
    posted_.wait(lock, [&] { return !tasks_.empty(); });
    auto task = std::move(tasks_.front());
    tasks_.pop_front();
    lock.unlock();
    task();
  }
  std::size_t pending() {
    std::lock_guard lock(mutex_);
    return tasks_.size();
  }

 private:
  std::mutex mutex_;
  std::condition_variable posted_;
  std::deque<std::function<void()>> tasks_;
};

TEST(PoolTlGridSource, TheModelsGridComesBackOnTheCoreNeverInsideRequest) {
  gram::ModelPool pool({1, 4, 1 << 20}, gram::make_builtin_engine());
  Core core;
  PoolTlGridSource source(pool, core.executor());
  ModelRun run;
  run.environment = small_env();
  int answers = 0;
  ModelAnswer got;
  source.request(run, [&](ModelAnswer a) {
    ++answers;
    got = std::move(a);
  });
  EXPECT_EQ(answers, 0);
  core.run_one();
  ASSERT_EQ(answers, 1);
  ASSERT_TRUE(got.tl) << got.error;
  const auto expected = gram::compute_transmission_loss(small_env(), {1});
  ASSERT_EQ(got.tl->tl_db.size(), expected.tl_db.size());
  EXPECT_EQ(std::memcmp(got.tl->tl_db.data(), expected.tl_db.data(), expected.tl_db.size() * sizeof(double)), 0);

  // Asked again: a cache hit answered inside submit(), still posted.
  answers = 0;
  source.request(run, [&](ModelAnswer a) {
    ++answers;
    got = std::move(a);
  });
  EXPECT_EQ(answers, 0);
  EXPECT_EQ(core.pending(), 1u);
  core.run_one();
  EXPECT_EQ(answers, 1);
  EXPECT_TRUE(got.tl);
}

TEST(PoolTlGridSource, TheDelaySpreadOfOneReceiverComesBack) {
  gram::ModelPool pool({1, 4, 1 << 20}, gram::make_builtin_engine());
  Core core;
  PoolTlGridSource source(pool, core.executor());
  ModelRun run;
  run.kind = ModelRun::Kind::kDelaySpread;
  run.environment = small_env();
  run.environment.set_irregular_receivers(true);
  run.environment.clear_receiver_depth_m();
  run.environment.clear_receiver_range_m();
  run.environment.add_receiver_depth_m(50);
  run.environment.add_receiver_range_m(800);
  ModelAnswer got;
  source.request(run, [&](ModelAnswer a) { got = std::move(a); });
  core.run_one();
  ASSERT_TRUE(got.delay_spread_s) << got.error;
  EXPECT_GT(*got.delay_spread_s, 0);
}

TEST(PoolTlGridSource, ThePoolsRefusalsReachThePhysicsAsErrors) {
  gram::ModelPool pool({1, 1, 1 << 20}, gram::make_builtin_engine());
  pool.pause();
  Core core;
  PoolTlGridSource source(pool, core.executor());
  ModelRun bad;
  bad.environment = small_env();
  bad.environment.set_frequency_hz(-1);
  ModelAnswer refused;
  source.request(bad, [&](ModelAnswer a) { refused = std::move(a); });
  core.run_one();
  EXPECT_FALSE(refused.tl);
  EXPECT_NE(refused.error.find("frequency_hz"), std::string::npos) << refused.error;

  ModelRun run;
  run.environment = small_env();
  ModelAnswer waiting, full;
  source.request(run, [&](ModelAnswer a) { waiting = std::move(a); });
  run.environment.set_source_depth_m(31);
  source.request(run, [&](ModelAnswer a) { full = std::move(a); });
  core.run_one();
  EXPECT_NE(full.error.find("queue_limit = 1"), std::string::npos) << full.error;
  pool.resume();
  core.run_one();
  EXPECT_TRUE(waiting.tl) << waiting.error;
}

}  // namespace
}  // namespace acomms::drivers
